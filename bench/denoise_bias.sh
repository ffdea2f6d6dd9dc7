#!/usr/bin/env bash
# The denoiser's error as bias and variance (docs/denoising.md, "How the candidates were chosen"):
#
#   bench/denoise_bias.sh BUILD [SCENE] [SPP] [SEEDS]   (scenes/cornell-box.yaml, 16, 8)
#
# Renders SCENE at 200 x 150 with --aovs for seeds 1..SEEDS, denoises each with `glint denoise`,
# and splits the denoised images' error against a 2048-spp reference into bias^2 and variance
# (bench/denoise_bias.py). The reference is bench/denoise.sh's when it exists ($OUT, default
# /tmp/glint-denoise, named by the scene file), else rendered there.
set -euo pipefail
build=$(cd "$1" && pwd)
here=$(cd "$(dirname "$0")/.." && pwd)
scene=${2:-scenes/cornell-box.yaml}
spp=${3:-16}
seeds=${4:-8}
glint=$build/apps/glint/glint
out=${OUT:-/tmp/glint-denoise}
name=$(basename "$scene" .yaml)
[[ $name == cornell-box ]] && name=cornell
mkdir -p "$out/bias"
ref=$out/$name-ref.exr
[[ -f $ref ]] || "$glint" render "$here/$scene" --width 200 --height 150 --spp 2048 -q -o "$ref"
images=()
for seed in $(seq 1 "$seeds"); do
  raw=$out/bias/$name-$spp-seed$seed.exr
  "$glint" render "$here/$scene" --width 200 --height 150 --spp "$spp" --seed "$seed" --aovs -q -o "$raw"
  "$glint" denoise "$raw" -o "${raw%.exr}-denoised.exr" -q
  images+=("${raw%.exr}-denoised.exr")
done
/usr/bin/python3 "$here/bench/denoise_bias.py" "$ref" "${images[@]}"
