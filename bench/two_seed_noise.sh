#!/usr/bin/env bash
# The noise of a render without a reference: two renders with different seeds, a and b; each
# one's relative variance is estimated per pixel and channel as (a - b)^2 / 2 / (m^2 + 0.01),
# m = (a + b) / 2, and the square root of its mean is printed (comparable to the relative RMSE
# of bench/compare_cycles.sh), with the render times and rays of both runs.
#
#   bench/two_seed_noise.sh GLINT_BINARY SCENE [glint render flags...]
#   e.g. (the Russian roulette study of docs/benchmarks.md):
#   for d in 3 4 5 6; do sed "s/max_depth: 16}/max_depth: 16, rr_depth: $d}/" scenes/cornell-box.yaml > /tmp/rr$d.yaml
#     bench/two_seed_noise.sh build/apps/glint/glint /tmp/rr$d.yaml --spp 64; done
set -euo pipefail
glint=$1 scene=$2
shift 2
out=$(mktemp -d)
runs=""
for s in 11 12; do
  runs="$runs $("$glint" render "$scene" --seed $s -o "$out/$s.exr" "$@" 2>&1 |
    sed -n 's/^rendered .* in \([0-9.]*\) s: \([0-9]*\) rays.*/\1 s \2 rays;/p')"
done
a="$out/11.exr" b="$out/12.exr"
sigma=$(oiiotool "$a" --ch R,G,B "$b" --ch R,G,B --sub --dup --mul --mulc 0.5 \
          "$a" --ch R,G,B "$b" --ch R,G,B --add --mulc 0.5 --dup --mul --addc 0.01 --div --printstats 2>&1 |
        sed -n 's/.*Stats Avg: \([0-9.e+-]*\) \([0-9.e+-]*\) \([0-9.e+-]*\).*/\1 \2 \3/p' |
        awk '{printf "%.4f", sqrt(($1 + $2 + $3) / 3)}')
echo "$scene: relative noise $sigma;$runs"
rm -rf "$out"
