#!/usr/bin/env bash
# glint against pbrt-v4 itself on a .pbrt file: both render the file as it is (its camera,
# film, sampler and integrator; --spp SPP for both when given), then glint_image_compare prints
# the channel means of each, how many 16x16 blocks agree within 5 %, and any named regions.
# pbrt-v4 is not a Debian package: build it with ../shared/peers/pbrt-v4-build.md and give its
# binary as PBRT. With GREY=1 every "rgb NAME" [r g b] of the file becomes its mean first (a
# copy beside the file), so that pbrt-v4's spectral light and glint's RGB light agree and what
# is left is transport and materials. Images and logs stay in OUT.
#
#   PBRT=/path/to/pbrt bench/compare_pbrt.sh [BUILD_DIR] SCENE.pbrt [SPP] [--region NAME X0 Y0 X1 Y1]...
#   env: THREADS (2), GREY=1, OUT (a new temporary folder), NOISE=1 (glint once more with another
#        seed, compared with its first image: the agreement noise alone allows at this spp)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:?usage: PBRT=... bench/compare_pbrt.sh BUILD_DIR SCENE.pbrt [SPP] [--region ...]}
scene=${2:?usage: PBRT=... bench/compare_pbrt.sh BUILD_DIR SCENE.pbrt [SPP] [--region ...]}
shift 2
spp=""
if [ $# -gt 0 ] && [[ $1 != --* ]]; then spp=$1; shift; fi
glint="$build/apps/glint/glint"
compare="$build/tools/glint_image_compare"
pbrt=${PBRT:?set PBRT to a pbrt-v4 binary (../shared/peers/pbrt-v4-build.md)}
threads=${THREADS:-2}
out=${OUT:-$(mktemp -d)}
mkdir -p "$out"
[ -x "$glint" ] && [ -x "$compare" ] || { echo "missing $glint or $compare: run make build" >&2; exit 1; }

name=$(basename "$scene" .pbrt)
if [ "${GREY:-0}" = 1 ]; then
  grey="$(dirname "$scene")/.grey-$(basename "$scene")"
  sed -E 's/("rgb [A-Za-z.]+"[[:space:]]*)\[[[:space:]]*([-0-9.eE+]+)[[:space:]]+([-0-9.eE+]+)[[:space:]]+([-0-9.eE+]+)[[:space:]]*\]/\1[ GREY(\2,\3,\4) ]/g' "$scene" |
    awk '{ while (match($0, /GREY\([^)]*\)/)) { split(substr($0, RSTART + 5, RLENGTH - 6), v, ",");
           m = (v[1] + v[2] + v[3]) / 3; $0 = substr($0, 1, RSTART - 1) m " " m " " m substr($0, RSTART + RLENGTH) } print }' > "$grey"
  trap 'rm -f "$grey"' EXIT
  scene=$grey
fi

spp_flag=()
[ -n "$spp" ] && spp_flag=(--spp "$spp")
echo "scene $scene${spp:+, $spp spp}, $threads threads"
start=$(date +%s.%N)
"$pbrt" --nthreads "$threads" ${spp:+--spp "$spp"} --outfile "$out/$name-pbrt.exr" "$scene" > "$out/$name-pbrt.log" 2>&1
mid=$(date +%s.%N)
"$glint" render "$scene" -q --threads "$threads" "${spp_flag[@]}" -o "$out/$name-glint.exr" > "$out/$name-glint.log" 2>&1
end=$(date +%s.%N)
awk -v a="$start" -v b="$mid" -v c="$end" 'BEGIN { printf "time           pbrt-v4 %.1f s, glint %.1f s\n", b - a, c - b }'
echo "A = glint, B = pbrt-v4 ($out)"
"$compare" "$out/$name-glint.exr" "$out/$name-pbrt.exr" "$@"
if [ "${NOISE:-0}" = 1 ]; then
  "$glint" render "$scene" -q --threads "$threads" "${spp_flag[@]}" --seed 7 -o "$out/$name-glint-seed7.exr" > /dev/null 2>&1
  echo "noise floor: A = glint, B = glint with another seed"
  "$compare" "$out/$name-glint.exr" "$out/$name-glint-seed7.exr" "$@"
fi
