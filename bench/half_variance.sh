#!/usr/bin/env bash
# How well the half images measure the noise (docs/denoising.md, "Half buffers that are stratified"):
#
#   bench/half_variance.sh BUILD SCENE SPP [RENDERS] [WIDTH]
#
# Renders SCENE RENDERS times (default 24) at SPP with seeds 1..RENDERS, WIDTH (default 100) by
# 3/4 of it, with --aovs; prints the variance of the pixel's mean over the renders (brute force,
# R channel, mean over pixels), the mean half-buffer estimate (even.R - odd.R)^2 / 4, and their
# ratio. All arithmetic by oiiotool.
set -euo pipefail
build=$(cd "$1" && pwd)
scene=$2
spp=$3
renders=${4:-24}
width=${5:-100}
height=$(( width * 3 / 4 ))
glint=$build/apps/glint/glint
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mean_of() { oiiotool "$1" --printstats 2>&1 | sed -n 's/.*Stats Avg: \([0-9.e+-]*\).*/\1/p'; }
for ((s = 1; s <= renders; ++s)); do
  f=$work/r$s.exr
  "$glint" render "$scene" --width "$width" --height "$height" --spp "$spp" --seed "$s" --aovs -q -o "$f"
  oiiotool "$f" --ch R -o "$work/x.exr"
  oiiotool "$f" --ch R --dup --mul -o "$work/xx.exr"
  oiiotool "$f" --ch even.R "$f" --ch odd.R --sub --dup --mul -o "$work/dd.exr"
  if ((s == 1)); then
    for k in x xx dd; do mv "$work/$k.exr" "$work/sum_$k.exr"; done
  else
    for k in x xx dd; do oiiotool "$work/sum_$k.exr" "$work/$k.exr" --add -o "$work/sum_$k.exr"; done
  fi
done
# variance over renders = (sum x^2 - (sum x)^2 / K) / (K - 1); estimate = sum d^2 / 4K.
oiiotool "$work/sum_xx.exr" "$work/sum_x.exr" --dup --mul --divc "$renders" --sub --divc $((renders - 1)) -o "$work/var.exr"
oiiotool "$work/sum_dd.exr" --divc $((4 * renders)) -o "$work/est.exr"
variance=$(mean_of "$work/var.exr")
estimate=$(mean_of "$work/est.exr")
printf "%s at %s spp, %d renders: variance %.3g, half-buffer estimate %.3g, ratio %.2f\n" \
  "$(basename "$scene")" "$spp" "$renders" "$variance" "$estimate" "$(awk -v a="$estimate" -v b="$variance" 'BEGIN { print a / b }')"
