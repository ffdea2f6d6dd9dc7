# The pytest suite of the Python module (docs/python.md), run by ctest (tests/CMakeLists.txt) with
# PYTHONPATH at the build's python/ folder, GLINT_CLI at the command line binary and
# GLINT_SOURCE_DIR at the checkout.
import os
import pathlib

import pytest

SOURCE = pathlib.Path(os.environ.get("GLINT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
CLI = os.environ.get("GLINT_CLI", str(SOURCE / "build" / "apps" / "glint" / "glint"))


@pytest.fixture
def source():
    return SOURCE


@pytest.fixture
def cli():
    return CLI


def plane_scene(albedo=(0.2, 0.4, 0.6), distance=5.0, width=32, height=24, spp=4):
    """A diffuse square filling the view, facing the camera at `distance`, under a white sky."""
    return {
        "camera": {"type": "look_at", "from": [0, 0, -distance], "to": [0, 0, 0], "up": [0, 1, 0], "fov": 30},
        "film": {"width": width, "height": height},
        "sampler": {"spp": spp},
        "integrator": {"type": "path", "max_depth": 4},
        "background": {"type": "constant", "color": [1, 1, 1]},
        "objects": [{"type": "quad", "corner": [-10, -10, 0], "edge1": [0, 20, 0], "edge2": [20, 0, 0],
                     "material": {"type": "diffuse", "albedo": list(albedo)}}],
    }
