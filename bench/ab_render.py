#!/usr/bin/env python3
"""Two glint binaries (before and after a change) rendering one scene in alternating rounds, whole
process timed: each round runs A then B (B then A every other round), the ratio B/A of that
round's times is taken, so both see the shared machine in nearly the same state. Prints the median
times and the median ratio over the rounds, and each ratio; checks the two images' pixels agree.

    bench/ab_render.py A_BINARY B_BINARY SCENE ROUNDS [glint render flags...]
"""
import statistics
import subprocess
import sys
import tempfile
import time

if len(sys.argv) < 5:
    sys.exit(__doc__)
a, b, scene, rounds, flags = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), sys.argv[5:]
out = tempfile.mkdtemp()
times = {"A": [], "B": []}
ratios = []
for r in range(rounds):
    t = {}
    for name, binary in (("A", a), ("B", b)) if r % 2 == 0 else (("B", b), ("A", a)):
        t0 = time.perf_counter()
        subprocess.run([binary, "render", scene, "-q", "-o", f"{out}/{name}.exr"] + flags, check=True)
        t[name] = time.perf_counter() - t0
        times[name].append(t[name])
    ratios.append(t["B"] / t["A"])
same = subprocess.run(["idiff", "-q", "-fail", "0", "-warn", "0", f"{out}/A.exr", f"{out}/B.exr"]).returncode == 0
print(f"{scene}: A median {statistics.median(times['A']):.3f} s, B median {statistics.median(times['B']):.3f} s, "
      f"B/A median {statistics.median(ratios):.3f} over {rounds} rounds:", " ".join(f"{x:.3f}" for x in ratios))
print("pixels identical" if same else "pixels differ")
