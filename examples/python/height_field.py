#!/usr/bin/python3
"""A scene built from numpy: a height field (ripples on a pond) as a mesh whose positions, indices
and normals are numpy arrays, read by glint without passing through text. Run from the checkout
with PYTHONPATH=build/python:

    examples/python/height_field.py [out.png] [--quick]
"""
import sys

import numpy as np

import glint

quick = "--quick" in sys.argv
out = next((a for a in sys.argv[1:] if not a.startswith("--")), "height-field.png")
n = 64 if quick else 400                 # vertices along a side: 2 (n - 1)^2 triangles
width, height, spp = (48, 32, 4) if quick else (480, 320, 64)

# The surface y = f(x, z) on [-2, 2]^2: two ripples spreading and crossing.
x, z = np.meshgrid(np.linspace(-2, 2, n), np.linspace(-2, 2, n))
r1, r2 = np.hypot(x + 0.8, z - 0.5), np.hypot(x - 1.0, z + 0.3)
y = 0.08 * (np.cos(9 * r1) * np.exp(-r1) + np.cos(11 * r2) * np.exp(-1.3 * r2))
positions = np.stack([x, y, z], axis=-1).reshape(-1, 3)

# Its normals from the slopes: (-dy/dx, 1, -dy/dz), normalised.
dy_dz, dy_dx = np.gradient(y, z[:, 0], x[0, :])
normals = np.stack([-dy_dx, np.ones_like(y), -dy_dz], axis=-1).reshape(-1, 3)
normals /= np.linalg.norm(normals, axis=1, keepdims=True)

# Two triangles a grid cell, wound so that their fronts face up (+y) in glint's left-handed frame.
idx = np.arange(n * n).reshape(n, n)
a, b, c, d = idx[:-1, :-1].ravel(), idx[:-1, 1:].ravel(), idx[1:, 1:].ravel(), idx[1:, :-1].ravel()
indices = np.concatenate([np.stack([a, c, b], 1), np.stack([a, d, c], 1)])

scene = glint.load_dict({
    "camera": {"type": "look_at", "from": [0, 2.2, -4.2], "to": [0, -0.1, 0], "up": [0, 1, 0], "fov": 38},
    "film": {"width": width, "height": height},
    "integrator": {"type": "path", "max_depth": 8},
    "background": {"type": "sky", "horizon": [1, 0.95, 0.9], "zenith": [0.35, 0.55, 0.9]},
    "lights": [{"type": "directional", "direction": [-0.4, -1, 0.6], "intensity": [3, 2.8, 2.5], "angular_diameter": 2}],
    "objects": [
        {"type": "mesh", "positions": positions, "indices": indices, "normals": normals,
         "material": {"type": "plastic", "albedo": [0.05, 0.25, 0.3], "roughness": 0.15}},
    ],
})
image = glint.render(scene, spp=spp, seed=1)
glint.write(out, image)
print(f"{len(indices):,} triangles from numpy; wrote {out} ({image.shape[1]}x{image.shape[0]}, {image.spp} spp)")
