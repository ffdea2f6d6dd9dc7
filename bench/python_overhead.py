#!/usr/bin/python3
"""What the Python module costs over the command line (docs/benchmarks.md, "Python module").

    PYTHONPATH=build/python bench/python_overhead.py build [runs]

1. A 64 x 64 render of the Cornell box (16 spp, 2 threads) through glint.render, against the
   same render by the command line (its whole process: start, load, render, write the EXR).
2. A mesh of about a million triangles (a 709 x 709 height field) loaded from numpy arrays,
   against the same mesh read from a binary PLY file: each rendered once at 16 x 16, 1 spp, so the
   times hold the load and the BVH build; the load alone is the difference.
Medians of `runs` runs (default 7), printed with the ratios.
"""
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import glint

build = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "build")
runs = int(sys.argv[2]) if len(sys.argv) > 2 else 7
cli = build / "apps" / "glint" / "glint"
root = pathlib.Path(__file__).resolve().parents[1]


def median_time(fn):
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


with tempfile.TemporaryDirectory() as tmp:
    scene = root / "scenes" / "cornell-box.yaml"
    args = ["--width", "64", "--height", "64", "--spp", "16", "--threads", "2", "--seed", "1"]
    out = os.path.join(tmp, "a.exr")
    t_cli = median_time(lambda: subprocess.run([cli, "render", scene, "-o", out, "--quiet", *args], check=True))
    t_py = median_time(lambda: glint.render(scene, width=64, height=64, spp=16, threads=2, seed=1))
    print(f"64x64 cornell-box 16 spp, 2 threads: CLI {t_cli * 1000:.1f} ms, glint.render {t_py * 1000:.1f} ms, "
          f"ratio {t_py / t_cli:.3f}")

    n = 709  # 2 (n - 1)^2 = 1,002,528 triangles
    x, z = np.meshgrid(np.linspace(-1, 1, n, dtype=np.float32), np.linspace(-1, 1, n, dtype=np.float32))
    y = 0.1 * np.sin(8 * x) * np.cos(8 * z)
    positions = np.stack([x, y, z], axis=-1).reshape(-1, 3).astype(np.float32)
    idx = np.arange(n * n, dtype=np.uint32).reshape(n, n)
    a, b, c, d = idx[:-1, :-1].ravel(), idx[:-1, 1:].ravel(), idx[1:, 1:].ravel(), idx[1:, :-1].ravel()
    indices = np.concatenate([np.stack([a, c, b], 1), np.stack([a, d, c], 1)]).astype(np.uint32)
    ply = os.path.join(tmp, "field.ply")
    with open(ply, "wb") as f:
        f.write(f"ply\nformat binary_little_endian 1.0\nelement vertex {len(positions)}\n"
                "property float x\nproperty float y\nproperty float z\n"
                f"element face {len(indices)}\nproperty list uchar uint vertex_indices\nend_header\n".encode())
        f.write(positions.tobytes())
        faces = np.zeros(len(indices), dtype=[("n", "u1"), ("i", "<u4", 3)])
        faces["n"], faces["i"] = 3, indices
        f.write(faces.tobytes())
    base = {"camera": {"type": "look_at", "from": [0, 2, -2], "to": [0, 0, 0], "up": [0, 1, 0], "fov": 40},
            "film": {"width": 16, "height": 16}, "integrator": {"type": "path", "max_depth": 1},
            "background": {"type": "sky"}}

    def from_numpy():
        s = glint.load_dict(dict(base, objects=[{"type": "mesh", "positions": positions, "indices": indices}]))
        glint.render(s, spp=1, threads=2)

    def from_ply():
        s = glint.load_dict(dict(base, objects=[{"type": "mesh", "file": ply}]))
        glint.render(s, spp=1, threads=2)

    t_load = median_time(lambda: glint.load_dict(dict(base, objects=[
        {"type": "mesh", "positions": positions, "indices": indices}])))
    t_np, t_ply = median_time(from_numpy), median_time(from_ply)
    print(f"{len(indices):,} triangles: from numpy {t_np:.3f} s (load_dict alone {t_load:.3f} s), "
          f"from PLY {t_ply:.3f} s, ratio {t_np / t_ply:.3f}")
