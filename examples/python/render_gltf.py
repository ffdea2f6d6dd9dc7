#!/usr/bin/python3
"""Renders a glTF file as `glint render model.gltf` does (its own camera if it has one, else framed
whole, under a sky), then again with a scene of our own around it. Run from the checkout with
PYTHONPATH=build/python:

    examples/python/render_gltf.py [out.png] [--model model.gltf] [--quick]
"""
import pathlib
import sys

import numpy as np

import glint

root = pathlib.Path(__file__).resolve().parents[2]
argv = sys.argv[1:]
model = root / "tests" / "data" / "khronos" / "BoxTextured.gltf"
if "--model" in argv:
    i = argv.index("--model")
    model = pathlib.Path(argv[i + 1])
    del argv[i:i + 2]
quick = "--quick" in argv
out = next((a for a in argv if not a.startswith("--")), "gltf.png")
size, spp = (32, 4) if quick else (320, 64)

# 1. The file on its own.
alone = glint.render(glint.load(model), width=size, height=size, spp=spp, seed=1)

# 2. The file placed in a scene: twice, turned, on a floor, under an environment map.
placed = glint.render({
    "camera": {"type": "look_at", "from": [0, 2.5, -5], "to": [0, 0.4, 0], "up": [0, 1, 0], "fov": 35},
    "film": {"width": size, "height": size},
    "integrator": {"type": "path", "max_depth": 6},
    "background": {"type": "environment", "filename": str(root / "scenes" / "textures" / "sky.exr")},
    "objects": [
        {"type": "mesh", "file": str(model), "transform": [{"translate": [-1, 0.5, 0]}]},
        {"type": "mesh", "file": str(model),
         "transform": [{"rotate": {"angle": 35, "axis": [0, 1, 0]}}, {"translate": [1, 0.5, 0.5]}]},
        {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": {"type": "diffuse"}},
    ],
}, spp=spp, seed=1)
glint.write(out, np.concatenate([alone, placed], axis=1))
print(f"wrote {out}: {model.name} alone (left) and placed twice (right)")
