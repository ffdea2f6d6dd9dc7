#!/usr/bin/env bash
# The denoiser against converged images (docs/benchmarks.md, "Denoising"):
#
#   bench/denoise.sh BUILD [WIDTH] [REF_SPP]      (SPPS="16 64 256" by default)
#
# For each scene: a reference at REF_SPP (default 4096), then renders at each of $SPPS with --aovs, each denoised by `glint denoise`; prints the relative MSE against the
# reference (mean over pixels and channels of (x - ref)^2 / (ref^2 + 0.01), by oiiotool) of the
# raw and the denoised image, and the seconds the filter took; then (bench/denoise_metrics.py,
# needs python3-opencv: GLINT_BENCH_DEPS=1 scripts/install-deps.sh) the SSIM of both and a
# classical baseline, OpenCV's non-local means on the raw image: its relative MSE, SSIM and
# seconds. The film is WIDTH (default 320)
# by 3/4 of it, whatever the scene's own size. Images are kept in $OUT (default /tmp/glint-denoise).
set -euo pipefail
build=$(cd "$1" && pwd)
width=${2:-320}
ref_spp=${3:-4096}
read -r -a spps <<<"${SPPS:-16 64 256}"
height=$(( width * 3 / 4 ))
glint=$build/apps/glint/glint
here=$(cd "$(dirname "$0")/.." && pwd)
out=${OUT:-/tmp/glint-denoise}
mkdir -p "$out"
source "$here/bench/image_error.sh"

scenes=(
  "cornell scenes/cornell-box.yaml"
  "bunny scenes/bunny.yaml"
  "materials scenes/materials.yaml"
  "fig14-soft scenes/seed/fig14-soft.yaml"
  "textures scenes/textures.yaml"
  "textures-lit scenes/textures-lit.yaml"
  "cloud scenes/volumes/cloud.yaml"
)
# The killeroos of the pbrt-v4 scene collection (the issue's sixth scene), when the shared models
# are there (not in this repository; docs/scene-format.md).
models=${GLINT_MODEL_PATH:-$here/../shared/models}
killeroos=$models/pbrt-v4-scenes/killeroos/killeroo-simple.pbrt
if [[ -f $killeroos ]]; then scenes+=("killeroos $killeroos"); else echo "denoise.sh: no $killeroos: no killeroos" >&2; fi
mse() { awk -v r="$1" 'BEGIN { printf "%.6f", r * r }'; }
metrics() { "$here/bench/denoise_metrics.py" "$@" 2>/dev/null || echo "- - - - - -"; }
/usr/bin/python3 -c "import cv2" 2>/dev/null ||
  echo "denoise.sh: no python3-opencv (GLINT_BENCH_DEPS=1 scripts/install-deps.sh): no SSIM, no baseline" >&2
printf "%-12s %6s %12s %12s %8s %8s %8s %8s %12s %8s %6s %4s\n" scene spp "raw relMSE" "denoised" "ratio" "filter s" \
  "raw SSIM" "SSIM" "OpenCV relMSE" "SSIM" "s" "h"
for entry in "${scenes[@]}"; do
  read -r name file <<<"$entry"
  [[ $file == /* ]] || file=$here/$file
  ref=$out/$name-ref.exr
  [[ -f $ref ]] || "$glint" render "$file" --width "$width" --height "$height" --spp "$ref_spp" -q -o "$ref"
  for spp in "${spps[@]}"; do
    raw=$out/$name-$spp.exr
    den=$out/$name-$spp-denoised.exr
    "$glint" render "$file" --width "$width" --height "$height" --spp "$spp" --aovs -q -o "$raw"
    secs=$("$glint" denoise "$raw" -o "$den" 2>&1 | sed -n 's/denoised in \([0-9.]*\) s/\1/p')
    r=$(mse "$(relative_rmse "$raw" "$ref")")
    d=$(mse "$(relative_rmse "$den" "$ref")")
    read -r s_raw s_den cv_mse cv_ssim cv_secs cv_h <<<"$(metrics "$ref" "$raw" "$den")"
    printf "%-12s %6s %12s %12s %8s %8s %8s %8s %12s %8s %6s %4s\n" "$name" "$spp" "$r" "$d" \
      "$(awk -v a="$r" -v b="$d" 'BEGIN { printf "%.2f", a / b }')" "$secs" "$s_raw" "$s_den" "$cv_mse" "$cv_ssim" "$cv_secs" "$cv_h"
  done
done
