#!/usr/bin/env bash
# What spectral mode costs against RGB mode, and how much colour noise it adds (docs/spectral.md,
# "Measured"):
#
#   bench/spectral.sh BUILD SCENE SPP [RUNS] [THREADS]
#
# Renders SCENE RUNS times (default 3) in each mode, the modes alternating so that both see the
# same machine, and prints each mode's median wall and user CPU time and their ratio. Then the
# noise per sample: each mode rendered with seeds 1 and 2, and from the difference d = a - b,
#   absolute: sqrt(mean(d^2) / 2), the RMS error of one render (the mean over pixels and channels);
#   relative: sqrt(mean(d^2 / 2 / (m^2 + 0.01))), m = (a + b) / 2, as bench/two_seed_noise.sh.
# The first is dominated by the brightest pixels (a light seen directly), the second by the dark.
set -euo pipefail
build=$(cd "$1" && pwd)
scene=$2
spp=$3
runs=${4:-3}
threads=${5:-2}
glint=$build/apps/glint/glint
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
for ((i = 1; i <= runs; ++i)); do
  for m in rgb spectral; do
    /usr/bin/time -f "%e %U" -o "$work/t" "$glint" render "$scene" --spp "$spp" --threads "$threads" \
      --"$m" -q -o "$work/t.exr"
    read -r wall user < "$work/t"
    echo "$wall" >> "$work/$m.wall"
    echo "$user" >> "$work/$m.user"
  done
done
stats() { oiiotool "$@" --printstats 2>&1 | sed -n 's/.*Stats Avg: \([0-9.e+-]*\) \([0-9.e+-]*\) \([0-9.e+-]*\).*/\1 \2 \3/p'; }
for m in rgb spectral; do
  for s in 1 2; do "$glint" render "$scene" --spp "$spp" --threads "$threads" --seed $s --"$m" -q -o "$work/$m$s.exr"; done
  a="$work/${m}1.exr" b="$work/${m}2.exr"
  abs=$(stats "$a" --ch R,G,B "$b" --ch R,G,B --sub --dup --mul --mulc 0.5 | awk '{printf "%.5f", sqrt(($1 + $2 + $3) / 3)}')
  rel=$(stats "$a" --ch R,G,B "$b" --ch R,G,B --sub --dup --mul --mulc 0.5 \
          "$a" --ch R,G,B "$b" --ch R,G,B --add --mulc 0.5 --dup --mul --addc 0.01 --div |
        awk '{printf "%.5f", sqrt(($1 + $2 + $3) / 3)}')
  echo "$abs $rel" > "$work/$m.noise"
done
read -r ra rr < "$work/rgb.noise"
read -r sa sr < "$work/spectral.noise"
rw=$(median < "$work/rgb.wall") sw=$(median < "$work/spectral.wall")
ru=$(median < "$work/rgb.user") su=$(median < "$work/spectral.user")
echo "$scene, $spp spp, $threads threads, medians of $runs:"
awk -v rw="$rw" -v sw="$sw" -v ru="$ru" -v su="$su" 'BEGIN {
  printf "  time  rgb %.2f s (%.2f CPU-s), spectral %.2f s (%.2f CPU-s): %.2fx wall, %.2fx CPU\n", rw, ru, sw, su, sw / rw, su / ru }'
awk -v ra="$ra" -v sa="$sa" -v rr="$rr" -v sr="$sr" 'BEGIN {
  printf "  noise absolute %.5f -> %.5f (%.2fx), relative %.5f -> %.5f (%.2fx)\n", ra, sa, sa / ra, rr, sr, sr / rr }'
