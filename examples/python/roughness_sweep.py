#!/usr/bin/python3
"""A parameter sweep: roughness 0 to 1 for a gold conductor (top row) and a red plastic (bottom),
rendered as one grid image. Run from the checkout with PYTHONPATH=build/python:

    examples/python/roughness_sweep.py [out.png] [--quick]
"""
import pathlib
import sys

import numpy as np

import glint

quick = "--quick" in sys.argv
out = next((a for a in sys.argv[1:] if not a.startswith("--")), "roughness-sweep.png")
size, spp = (24, 4) if quick else (128, 64)
sky = pathlib.Path(__file__).resolve().parents[2] / "scenes" / "textures" / "sky.exr"


def scene(material):
    return {
        "camera": {"type": "look_at", "from": [0, 1.2, -4], "to": [0, 0.9, 0], "up": [0, 1, 0], "fov": 30},
        "film": {"width": size, "height": size},
        "integrator": {"type": "path", "max_depth": 8},
        "background": {"type": "environment", "filename": str(sky)},
        "objects": [
            {"type": "sphere", "center": [0, 1, 0], "radius": 1, "material": material},
            {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0],
             "material": {"type": "diffuse", "albedo": {"type": "checker", "size": 0.5,
                                                        "even": [0.7, 0.7, 0.7], "odd": [0.2, 0.2, 0.2]}}},
        ],
    }


roughness = np.linspace(0, 1, 6)
rows = []
for kind in ("gold", "plastic"):
    row = []
    for r in roughness:
        material = ({"type": "conductor", "metal": "gold", "roughness": float(r)} if kind == "gold" else
                    {"type": "plastic", "albedo": [0.7, 0.08, 0.05], "roughness": float(r)})
        image = glint.render(scene(material), spp=spp, seed=1)
        row.append(image)
        print(f"{kind} roughness {r:.1f}: mean {image.mean():.3f}")
    rows.append(np.concatenate(row, axis=1))
grid = np.concatenate(rows, axis=0)
glint.write(out, grid)
print(f"wrote {out} ({grid.shape[1]}x{grid.shape[0]})")
