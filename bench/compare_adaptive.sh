#!/usr/bin/env bash
# Adaptive sampling at equal time: glint's (--noise-threshold) against glint's uniform sampling
# and against Blender Cycles' adaptive sampling with the same threshold, on the Cornell box
# (bench/cornell_cycles.py builds it in Cycles) and on glint's materials scene (glint only).
#
# Every error image is measured against a reference rendered with other seeds: for the Cornell
# box the mean of glint's and Cycles' REF_SPP images (as bench/compare_cycles.sh), for the
# materials scene glint's REF_SPP image. "Equal time" gives glint the render time Cycles (or
# glint's adaptive run) took, through --time. Times are render times as each program reports
# them (no start-up). Prints Markdown tables.
#
#   bench/compare_adaptive.sh [BUILD_DIR]
#   env: SIZE=256 (Cornell film side), THRESHOLD=0.01, MAX_SPP=1024, REF_SPP=1024, THREADS=2,
#        OUT (keep the images in this folder)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
size=${SIZE:-256}
threshold=${THRESHOLD:-0.01}
max_spp=${MAX_SPP:-1024}
ref_spp=${REF_SPP:-1024}
threads=${THREADS:-2}
glint="$build/apps/glint/glint"
out=${OUT:-$(mktemp -d)}
mkdir -p "$out"
for tool in blender oiiotool python3; do
  command -v "$tool" >/dev/null || { echo "missing $tool: run GLINT_BENCH_DEPS=1 scripts/install-deps.sh" >&2; exit 1; }
done
. bench/image_error.sh

glint_run() {  # scene out.exr flags... -> "seconds spp-summary"
  local scene=$1 o=$2; shift 2
  "$glint" render "$scene" --threads "$threads" -o "$o" "$@" 2>&1 |
    sed -n 's/^rendered [0-9x]* at \(.*\) in \([0-9.]*\) s: .*/\2 \1/p'
}
cycles_run() {  # out.exr spp seed threshold -> seconds
  blender -b --factory-startup -P bench/cornell_cycles.py -- "$1" "$2" "$threads" "$3" "$size" "$4" 2>&1 |
    sed -n 's/^cycles render seconds: \([0-9.]*\)/\1/p'
}

cb=scenes/cornell-box.yaml
wh="--width $size --height $size"
echo "cornell: references" >&2
glint_run $cb "$out/cb-ref-g.exr" $wh --spp "$ref_spp" --seed 100 > /dev/null
cycles_run "$out/cb-ref-c.exr" "$ref_spp" 100 0 > /dev/null
oiiotool "$out/cb-ref-g.exr" --ch R,G,B "$out/cb-ref-c.exr" --ch R,G,B --add --mulc 0.5 -o "$out/cb-ref.exr"

echo "cornell: Cycles adaptive, glint adaptive, glint at Cycles' time" >&2
tc=$(cycles_run "$out/cb-cycles-adaptive.exr" "$max_spp" 7 "$threshold")
tc_uniform=$(cycles_run "$out/cb-cycles-64.exr" 64 7 0)
read -r tg ga_what < <(glint_run $cb "$out/cb-glint-adaptive.exr" $wh --spp "$max_spp" --seed 7 --noise-threshold "$threshold")
read -r tgt gt_what < <(glint_run $cb "$out/cb-glint-adaptive-ctime.exr" $wh --spp "$max_spp" --seed 7 --noise-threshold "$threshold" --time "$tc")
read -r tgu gu_what < <(glint_run $cb "$out/cb-glint-uniform-ctime.exr" $wh --spp "$max_spp" --seed 7 --time "$tc")
read -r tgu2 gu2_what < <(glint_run $cb "$out/cb-glint-uniform-gtime.exr" $wh --spp "$max_spp" --seed 7 --time "$tg")
read -r tg64 g64_what < <(glint_run $cb "$out/cb-glint-64.exr" $wh --spp 64 --seed 7)

m=scenes/materials.yaml
mwh="--width 320 --height 240"
echo "materials" >&2
glint_run $m "$out/m-ref.exr" $mwh --spp "$ref_spp" --seed 100 > /dev/null
read -r tm ma_what < <(glint_run $m "$out/m-adaptive.exr" $mwh --spp "$max_spp" --seed 7 --noise-threshold "$threshold")
read -r tmu mu_what < <(glint_run $m "$out/m-uniform.exr" $mwh --spp "$max_spp" --seed 7 --time "$tm")

row() { echo "| $1 | $2 | $3 | $(relative_rmse "$4" "$5") |"; }
echo "Cornell box ${size}x${size}, $threads threads, threshold $threshold, at most $max_spp spp; reference: mean of glint's and Cycles' $ref_spp-spp images"
echo
echo "| image | render time (s) | samples | relative RMSE |"
echo "|---|---|---|---|"
row "Cycles, uniform 64 spp" "$tc_uniform" "64 spp" "$out/cb-cycles-64.exr" "$out/cb-ref.exr"
row "glint, uniform 64 spp" "$tg64" "$g64_what" "$out/cb-glint-64.exr" "$out/cb-ref.exr"
row "Cycles, adaptive" "$tc" "at most $max_spp spp (Cycles does not report its count)" "$out/cb-cycles-adaptive.exr" "$out/cb-ref.exr"
row "glint, adaptive" "$tg" "$ga_what" "$out/cb-glint-adaptive.exr" "$out/cb-ref.exr"
row "glint, adaptive, --time = Cycles' adaptive time" "$tgt" "$gt_what" "$out/cb-glint-adaptive-ctime.exr" "$out/cb-ref.exr"
row "glint, uniform, --time = Cycles' adaptive time" "$tgu" "$gu_what" "$out/cb-glint-uniform-ctime.exr" "$out/cb-ref.exr"
row "glint, uniform, --time = glint's adaptive time" "$tgu2" "$gu2_what" "$out/cb-glint-uniform-gtime.exr" "$out/cb-ref.exr"
echo
echo "Materials scene 320x240, $threads threads, threshold $threshold, at most $max_spp spp; reference: glint at $ref_spp spp (seed 100)"
echo
echo "| image | render time (s) | samples | relative RMSE |"
echo "|---|---|---|---|"
row "glint, adaptive" "$tm" "$ma_what" "$out/m-adaptive.exr" "$out/m-ref.exr"
row "glint, uniform, --time = adaptive's time" "$tmu" "$mu_what" "$out/m-uniform.exr" "$out/m-ref.exr"
