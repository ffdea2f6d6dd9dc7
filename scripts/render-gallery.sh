#!/usr/bin/env bash
# Renders the article's figures (scenes/seed/*.yaml) and the examples in scenes/ into docs/images/.
#   scripts/render-gallery.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
glint="${1:-build}/apps/glint/glint"
mkdir -p docs/images
for scene in scenes/seed/*.yaml; do
  name=$(basename "$scene" .yaml)
  "$glint" render "$scene" -q -o "docs/images/$name.png"
  echo "docs/images/$name.png"
done
# Anti-aliased Figure 14 (16 stratified samples per pixel) beside the article's 1-sample one.
"$glint" render scenes/seed/fig14-reflections.yaml --spp 16 -q -o docs/images/fig14-reflections-16spp.png
echo docs/images/fig14-reflections-16spp.png
# The UV test texture first: scenes/textures.yaml uses it.
"$glint" render scenes/textures/uv-grid.yaml -q -o scenes/textures/uv-grid.png
for name in shapes fig14-dof textures; do
  "$glint" render "scenes/$name.yaml" -q -o "docs/images/$name.png"
  echo "docs/images/$name.png"
done
