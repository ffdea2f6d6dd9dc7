#!/usr/bin/env bash
# Renders the article's figures (scenes/seed/*.yaml) and the examples in scenes/ into docs/images/,
# and regenerates the committed inputs they use (the UV grid, the HDR sky).
#   scripts/render-gallery.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
glint="${1:-build}/apps/glint/glint"
"${1:-build}/tools/glint_make_sky" scenes/textures/sky.exr
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
for name in shapes fig14-dof textures materials; do
  "$glint" render "scenes/$name.yaml" -q -o "docs/images/$name.png"
  echo "docs/images/$name.png"
done
# The Cornell box at 1024 spp (a few minutes on 2 cores).
"$glint" render scenes/cornell-box.yaml --spp 1024 -q -o docs/images/cornell-box.png
echo docs/images/cornell-box.png
# The bunny in the Cornell box (the bunny comes from ../shared/models; see docs/scene-format.md).
"$glint" render scenes/bunny.yaml --spp 256 -q -o docs/images/bunny.png
echo docs/images/bunny.png
# The glTF test scene, written by scripts/make_gltf_scene.py (not committed), with its own camera.
gltf_dir=$(mktemp -d)
python3 scripts/make_gltf_scene.py "$gltf_dir" > /dev/null
"$glint" render "$gltf_dir/textured.glb" --spp 256 --width 480 --height 320 -q -o docs/images/gltf-textured.png
rm -rf "$gltf_dir"
echo docs/images/gltf-textured.png
# Volumes (scenes/volumes/; cloud.vdb is written by the build), and the four side by side for
# docs/scene-format.md.
"$glint" render scenes/volumes/fig14-fog.yaml --spp 1024 -q -o docs/images/fig14-fog.png
"$glint" render scenes/volumes/glass.yaml --spp 256 -q -o docs/images/glass.png
"$glint" render scenes/volumes/cloud.yaml --spp 256 -q -o docs/images/cloud.png
"$glint" render scenes/volumes/milk-bunny.yaml --spp 256 -q -o docs/images/milk-bunny.png
oiiotool docs/images/fig14-fog.png --resize 240x135 docs/images/glass.png --resize 240x135 \
  docs/images/cloud.png --resize 240x135 docs/images/milk-bunny.png --resize 240x135 \
  --mosaic 4x1 -o docs/images/volumes.png
echo docs/images/fig14-fog.png docs/images/glass.png docs/images/cloud.png docs/images/milk-bunny.png docs/images/volumes.png
# pbrt-v4 scenes (scenes/pbrt/), side by side for the README.
gallery_tmp=$(mktemp -d)
for name in cornell-box bunny materials; do
  "$glint" render "scenes/pbrt/$name.pbrt" -q -o "$gallery_tmp/$name.png"
done
oiiotool "$gallery_tmp/cornell-box.png" --resize 256x256 "$gallery_tmp/bunny.png" --resize 256x256 --mosaic 2x1 \
  -o "$gallery_tmp/ab.png"
oiiotool "$gallery_tmp/ab.png" "$gallery_tmp/materials.png" --resize 512x256 --mosaic 2x1 --resize 768x192 \
  -o docs/images/pbrt-scenes.png
rm -rf "$gallery_tmp"
echo docs/images/pbrt-scenes.png
# What pbrt files bring: alpha, diffusetransmission, mix, a uniformgrid medium, power.
features_tmp=$(mktemp -d)
"$glint" render scenes/pbrt/features.pbrt -q -o "$features_tmp/features.png"
oiiotool "$features_tmp/features.png" --resize 560x280 -o docs/images/pbrt-features.png
echo docs/images/pbrt-features.png
# The killeroos of the pbrt-v4 scene collection, when ../shared/models holds them (not in this
# repository; see docs/scene-format.md).
killeroos=../shared/models/pbrt-v4-scenes/killeroos/killeroo-simple.pbrt
if [[ -f $killeroos ]]; then
  "$glint" render "$killeroos" -q -o "$features_tmp/killeroos.png"
  oiiotool "$features_tmp/killeroos.png" --resize 350x350 -o docs/images/pbrt-killeroos.png
  echo docs/images/pbrt-killeroos.png
fi
rm -rf "$features_tmp"
