#!/usr/bin/python3
"""Comparing two renders: the Cornell box at 16 spp with and without the denoiser, each against a
1024-spp reference, by RMSE, and a picture of the three with the error maps. Run from the checkout
with PYTHONPATH=build/python:

    examples/python/compare_renders.py [out.png] [--quick]
"""
import pathlib
import sys

import numpy as np

import glint

root = pathlib.Path(__file__).resolve().parents[2]
quick = "--quick" in sys.argv
out = next((a for a in sys.argv[1:] if not a.startswith("--")), "compare.png")
size, spp, ref_spp = (32, 8, 64) if quick else (256, 16, 1024)

scene = glint.load(root / "scenes" / "cornell-box.yaml")  # read once, rendered three ways
reference = glint.render(scene, width=size, height=size, spp=ref_spp, seed=2)
noisy = glint.render(scene, width=size, height=size, spp=spp, seed=1)
denoised = glint.render(scene, width=size, height=size, spp=spp, seed=1, denoise=True)


def rmse(a, b):
    return float(np.sqrt(np.mean((np.asarray(a) - np.asarray(b)) ** 2)))


print(f"{spp} spp: RMSE {rmse(noisy, reference):.4f}; denoised: {rmse(denoised, reference):.4f} "
      f"(against {ref_spp} spp)")
# Top: noisy, denoised, reference. Bottom: |error| x 4 of the two.
error = [np.abs(x - reference) * 4 for x in (noisy, denoised)]
grid = np.concatenate([np.concatenate([noisy, denoised, reference], axis=1),
                       np.concatenate([*error, np.zeros_like(reference)], axis=1)], axis=0)
glint.write(out, grid)
print(f"wrote {out}")
