#!/usr/bin/env bash
# Two glint binaries (say, before and after a change) on one scene in alternating runs: each
# round runs `glint bench SCENE --accel ACCEL --threads T --runs 7 --width 640 --height 480` with
# A, then with B, and the ratio B/A of that round's rates is taken, so that both builds see the
# shared machine in nearly the same state. Prints the median ratio over the rounds, and each.
#
#   bench/ab_builds.sh A_BINARY B_BINARY SCENE [ROUNDS=8] [THREADS=1] [ACCEL=bvh]
set -euo pipefail
if [[ $# -lt 3 ]]; then sed -n '2,7p' "$0"; exit 2; fi
a=$1 b=$2 scene=$3 rounds=${4:-8} threads=${5:-1} accel=${6:-bvh}
for r in $(seq "$rounds"); do
  for bin in "$a" "$b"; do
    "$bin" bench "$scene" --accel "$accel" --threads "$threads" --runs 7 --width 640 --height 480 2>/dev/null |
      awk -v r="$r" -v which="$([[ $bin == "$a" ]] && echo A || echo B)" -v k="$accel" '$1==k {print r, which, $6, $7}'
  done
done | python3 -c '
import statistics, sys
runs = {}
for line in sys.stdin:
    r, which, primary, diffuse = line.split()
    runs.setdefault(r, {})[which] = (float(primary), float(diffuse))
pairs = [v for v in runs.values() if len(v) == 2]
for i, name in enumerate(("primary", "diffuse")):
    ratios = [v["B"][i] / v["A"][i] for v in pairs]
    print(f"{name}: B/A median {statistics.median(ratios):.3f} over {len(ratios)} rounds:",
          " ".join(f"{x:.2f}" for x in ratios))
'
