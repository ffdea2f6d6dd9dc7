#!/usr/bin/env bash
# Two glint binaries (before and after a change) rendering one scene in alternating runs: each
# round renders with A, then with B (`glint render SCENE --spp SPP --threads T`), and the ratio
# B/A of that round's render seconds (glint's summary line) is taken. Prints the median ratio
# over the rounds, each round's ratio, and whether the two images are identical.
#
#   bench/ab_render.sh A_BINARY B_BINARY SCENE [ROUNDS=7] [SPP=64] [THREADS=2]
set -euo pipefail
if [[ $# -lt 3 ]]; then sed -n '2,7p' "$0"; exit 2; fi
a=$1 b=$2 scene=$3 rounds=${4:-7} spp=${5:-64} threads=${6:-2}
tmp=$(mktemp -d)
for r in $(seq "$rounds"); do
  for which in A B; do
    bin=$a; [[ $which == B ]] && bin=$b
    s=$("$bin" render "$scene" --spp "$spp" --threads "$threads" -o "$tmp/$which.exr" 2>&1 |
        sed -n 's/^rendered .* in \([0-9.]*\) s:.*/\1/p')
    echo "$r $which $s"
  done
done | python3 -c '
import statistics, sys
runs = {}
for line in sys.stdin:
    r, which, s = line.split()
    runs.setdefault(r, {})[which] = float(s)
ratios = [v["B"] / v["A"] for v in runs.values() if len(v) == 2]
a = statistics.median(v["A"] for v in runs.values()); b = statistics.median(v["B"] for v in runs.values())
print(f"render seconds: A median {a:.3f}, B median {b:.3f}; B/A median {statistics.median(ratios):.3f} over "
      f"{len(ratios)} rounds:", " ".join(f"{x:.3f}" for x in ratios))
'
if oiiotool "$tmp/A.exr" "$tmp/B.exr" --diff 2>&1 | grep -q "PASS"; then
  idiff -fail 0 -warn 0 "$tmp/A.exr" "$tmp/B.exr" > /dev/null && echo "images: identical pixels" || echo "images: differ"
else
  echo "images: differ"
fi
rm -rf "$tmp"
