#!/usr/bin/env bash
# Texture filtering at 1 spp against a 1024-spp reference with a box pixel filter and no texture
# filtering (the pixel's true mean), on scenes/texture-filtering.yaml (a receding checker and image
# texture) and scenes/texture-filtering-mirrors.yaml (the same floor in a chrome ball and through a
# glass ball): relative RMSE of each --texture-filter, and render times (medians of RUNS) against
# `none` on the scenes and on the gallery's textured path-traced scenes. Prints Markdown tables.
#
#   bench/texture_filtering.sh [BUILD_DIR]
#   env: RUNS=5, REF_SPP=1024, THREADS=2, OUT (keep the images)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
runs=${RUNS:-5}
ref_spp=${REF_SPP:-1024}
threads=${THREADS:-2}
glint="$build/apps/glint/glint"
out=${OUT:-$(mktemp -d)}
mkdir -p "$out"
. bench/image_error.sh
cp -r scenes/textures "$out/"
median() { sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }
seconds() {  # scene flags... -> median render seconds
  local scene=$1; shift
  for r in $(seq 1 "$runs"); do
    "$glint" render "$scene" --threads "$threads" -o "$out/t.exr" "$@" 2>&1 |
      sed -n 's/^rendered .* in \([0-9.]*\) s: .*/\1/p'
  done | median
}
echo "| scene | --texture-filter | relative RMSE at 1 spp | / none's | relative MSE / none's |"
echo "|---|---|---:|---:|---:|"
for name in texture-filtering texture-filtering-mirrors; do
  sed 's/^film: {\(.*\)}$/film: {\1, filter: {type: box}}/' "scenes/$name.yaml" > "$out/$name.yaml"
  "$glint" render "$out/$name.yaml" --spp "$ref_spp" --texture-filter none --threads "$threads" -q -o "$out/$name-ref.exr"
  for f in none trilinear ewa; do
    "$glint" render "$out/$name.yaml" --spp 1 --texture-filter "$f" --threads "$threads" -q -o "$out/$name-$f.exr"
    e=$(relative_rmse "$out/$name-$f.exr" "$out/$name-ref.exr")
    [[ $f == none ]] && e_none=$e
    echo "| $name | $f | $e | $(awk -v a="$e" -v b="$e_none" 'BEGIN {printf "%.3f | %.3f", a / b, (a / b)^2}') |"
  done
done
echo
echo "| scene | spp | none (s) | ewa (s) | ewa / none |"
echo "|---|---:|---:|---:|---:|"
for spec in "scenes/texture-filtering.yaml 64" "scenes/texture-filtering-mirrors.yaml 64" "scenes/gltf-layers.yaml 16" \
            "scenes/materials.yaml 16"; do
  read -r scene spp <<< "$spec"
  tn=$(seconds "$scene" --spp "$spp" --texture-filter none)
  te=$(seconds "$scene" --spp "$spp" --texture-filter ewa)
  echo "| $scene | $spp | $tn | $te | $(awk -v a="$te" -v b="$tn" 'BEGIN {printf "%.3f", a / b}') |"
done
echo "Images in $out"
