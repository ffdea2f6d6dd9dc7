#!/usr/bin/env python3
"""Ratios glint bvh / Embree per scene and thread count, from one or more outputs of
bench/compare_embree.sh (markdown tables): build time, primary and diffuse Mrays/s, the median
over the runs and each run's ratio. Runs of the whole script at different times see the shared
machine in different states; the median of their per-run ratios is what docs/benchmarks.md quotes.

    bench/compare_embree.sh build 5 > run1.md   # (and run2.md, run3.md)
    bench/embree_ratios.py run1.md run2.md run3.md
"""
import statistics
import sys

SCENES = ["bunny.yaml", "textured.glb", "cube-1m.ply", "latlong-1m.ply"]


def read(path):
    rows = {}
    with open(path) as f:
        for line in f:
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if len(cells) < 9 or cells[3] not in ("bvh", "sbvh", "embree"):
                continue
            rows[(cells[0], cells[2], cells[3])] = (float(cells[4]), float(cells[7]), float(cells[8]))
    return rows


def main(paths):
    if not paths:
        sys.exit(__doc__)
    runs = [read(p) for p in paths]
    keys = sorted({(s, t) for r in runs for (s, t, _) in r},
                  key=lambda k: (SCENES.index(k[0]) if k[0] in SCENES else len(SCENES), k[0], k[1]))
    print("| scene | threads | build time | primary | diffuse |")
    print("|---|---|---|---|---|")
    for scene, threads in keys:
        cells = []
        for i in range(3):
            ratios = [r[(scene, threads, "bvh")][i] / r[(scene, threads, "embree")][i]
                      for r in runs if (scene, threads, "bvh") in r and (scene, threads, "embree") in r]
            each = " ".join(f"{x:.2f}" for x in ratios)
            cells.append(f"**{statistics.median(ratios):.2f}** ({each})" if len(ratios) > 1
                         else f"{ratios[0]:.2f}")
        print(f"| {scene} | {threads} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main(sys.argv[1:])
