"""glint inside Blender against Cycles at equal time, on the Blender test's scene (docs/blender.md):

    GLINT_PYTHON=build/python/glint blender -b --factory-startup --python bench/blender_equal_time.py -- \\
        [SIZE] [SPP] [REF_SPP] [RUNS]        (defaults 128 64 4096 3; 2 threads)

The reference is the mean of both engines' REF_SPP images (other seeds). Each run renders the scene
with Cycles at SPP, then with glint at SPP, then with glint given Cycles' time as its time limit,
each through bpy.ops.render.render timed from the outside (export and scene sync included, as a
user waits for them). Error: relative RMSE, sqrt(mean((x - ref)^2 / (ref^2 + 0.01))) over pixels
and channels. Printed: medians over the runs, and the ratio of glint's error at Cycles' time to
Cycles' error, measured directly and from glint's error at SPP scaled by sqrt(its time / Cycles'
time) (Monte Carlo error falls as 1 / sqrt(time)).
"""
import os
import pathlib
import statistics
import sys
import tempfile
import time

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "blender"))
sys.path.insert(0, str(ROOT / "tests" / "blender"))
args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
os.environ["GLINT_BLENDER_SIZE"] = args[0] if len(args) > 0 else "128"
import glint as addon  # noqa: E402  (the add-on: blender/glint)
from scenes import build_scene, render  # noqa: E402

SPP = int(args[1]) if len(args) > 1 else 64
REF_SPP = int(args[2]) if len(args) > 2 else 4096
RUNS = int(args[3]) if len(args) > 3 else 3


def timed(scene, engine, path, spp, seed, limit=0.0):
    scene.glint.time_limit = limit
    start = time.perf_counter()
    image = render(scene, engine, path, spp, seed)
    return image, time.perf_counter() - start


def relative_rmse(x, ref):
    return float(np.sqrt(np.mean((x - ref) ** 2 / (ref ** 2 + 0.01))))


def main():
    addon.register()
    scene = build_scene()
    with tempfile.TemporaryDirectory() as folder:
        tmp = pathlib.Path(folder)
        print(f"reference: both engines at {REF_SPP} spp, {scene.render.resolution_x} x {scene.render.resolution_y}",
              flush=True)
        ref_g, t_ref_g = timed(scene, "GLINT", tmp / "ref-glint.exr", REF_SPP, 1000)
        ref_c, t_ref_c = timed(scene, "CYCLES", tmp / "ref-cycles.exr", REF_SPP, 1000)
        ref = 0.5 * (ref_g + ref_c)
        print(f"reference times: glint {t_ref_g:.1f} s, Cycles {t_ref_c:.1f} s; the two references differ by "
              f"relative RMSE {relative_rmse(ref_g, ref_c):.4f}", flush=True)
        rows = []
        for run in range(RUNS):
            seed = 1 + run
            c, t_c = timed(scene, "CYCLES", tmp / "c.exr", SPP, seed)
            g, t_g = timed(scene, "GLINT", tmp / "g.exr", SPP, seed)
            # As many passes as fit in Cycles' time (the samples cap far above what fits).
            e, t_e = timed(scene, "GLINT", tmp / "e.exr", 1 << 20, seed, limit=t_c)
            row = dict(t_c=t_c, t_g=t_g, t_e=t_e, err_c=relative_rmse(c, ref), err_g=relative_rmse(g, ref),
                       err_e=relative_rmse(e, ref))
            row["scaled"] = row["err_g"] * np.sqrt(t_g / t_c) / row["err_c"]
            row["direct"] = row["err_e"] / row["err_c"]
            rows.append(row)
            print("run {}: Cycles {:.2f} s err {:.4f}; glint {:.2f} s err {:.4f}; glint in Cycles' time "
                  "{:.2f} s err {:.4f}".format(run + 1, t_c, row["err_c"], t_g, row["err_g"], t_e, row["err_e"]),
                  flush=True)
        med = {k: statistics.median(r[k] for r in rows) for k in rows[0]}
        print(f"\n| engine | {SPP} spp time (s) | relative RMSE |")
        print("|---|---:|---:|")
        print(f"| Cycles | {med['t_c']:.2f} | {med['err_c']:.4f} |")
        print(f"| glint | {med['t_g']:.2f} | {med['err_g']:.4f} |")
        print(f"| glint, time limit = Cycles' time | {med['t_e']:.2f} | {med['err_e']:.4f} |")
        print(f"\nglint's error at Cycles' time / Cycles' error: {med['direct']:.3f} (rendered with the time limit), "
              f"{med['scaled']:.3f} (from {SPP} spp, scaled by sqrt(time)); speed at equal spp: "
              f"{med['t_c'] / med['t_g']:.2f}x Cycles'")


try:
    main()
finally:
    sys.stdout.flush()
    os._exit(0)
