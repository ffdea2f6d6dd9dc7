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
# glTF as found in the wild: the Khronos sample models of tests/data/khronos, framed by glint (no
# camera in the files but Cameras'), and BoxVertexColors again after Draco's own transcoder.
khronos_tmp=$(mktemp -d)
for name in Box BoxTextured BoxVertexColors Cameras SimpleSparseAccessor; do
  "$glint" render "tests/data/khronos/$name.gltf" --spp 64 --width 320 --height 240 -q -o "$khronos_tmp/$name.png"
done
if command -v draco_transcoder > /dev/null; then
  draco_transcoder -i tests/data/khronos/BoxVertexColors.gltf -o "$khronos_tmp/draco.gltf" > /dev/null
  "$glint" render "$khronos_tmp/draco.gltf" --spp 64 --width 320 --height 240 -q -o "$khronos_tmp/Draco.png"
else
  cp "$khronos_tmp/BoxVertexColors.png" "$khronos_tmp/Draco.png"
fi
oiiotool "$khronos_tmp/Box.png" "$khronos_tmp/BoxTextured.png" "$khronos_tmp/BoxVertexColors.png" \
  "$khronos_tmp/Cameras.png" "$khronos_tmp/SimpleSparseAccessor.png" "$khronos_tmp/Draco.png" \
  --mosaic 3x2 --resize 720x360 -o docs/images/gltf-khronos.png
echo docs/images/gltf-khronos.png
# Alpha and texture-coordinate sets: scripts/make_gltf_alpha.py's five quads in front of a checker
# wall (left to right: MASK texture, BLEND 0.25, MASK by vertex alpha, TEXCOORD_1, quantized).
python3 scripts/make_gltf_alpha.py "$khronos_tmp" > /dev/null
cat > "$khronos_tmp/alpha.yaml" <<'YAML'
camera: {type: look_at, from: [22, 9, -30], to: [22, 2, 0], fov: 40}
film: {width: 800, height: 300, tonemap: aces}
sampler: {spp: 128}
integrator: {type: path, max_depth: 8}
materials:
  wall: {type: diffuse, albedo: {type: checker, size: 1, even: [0.8, 0.8, 0.8], odd: [0.15, 0.15, 0.15]}}
objects:
  - {type: quad, corner: [-10, 0, 3], edge1: [0, 12, 0], edge2: [70, 0, 0], material: wall}
  - {type: quad, corner: [-10, 0, -30], edge1: [0, 0, 33], edge2: [70, 0, 0], material: wall}
  - {type: mesh, file: alpha.gltf}
YAML
"$glint" render "$khronos_tmp/alpha.yaml" -q -o docs/images/gltf-alpha.png
echo docs/images/gltf-alpha.png
rm -rf "$khronos_tmp"
# glTF's material extensions as pbr keys: clear coat, sheen, specular.
"$glint" render scenes/gltf-layers.yaml -q -o docs/images/gltf-layers.png
echo docs/images/gltf-layers.png
# The denoiser (docs/denoising.md): SCENE at 16 spp, the same denoised, and at SPP, side by side.
#   denoise_strip SCENE WIDTH HEIGHT SPP OUT
denoise_strip() {
  local tmp
  tmp=$(mktemp -d)
  for spp in 16 "$4"; do
    "$glint" render "$1" --width "$2" --height "$3" --spp "$spp" -q -o "$tmp/$spp.png"
  done
  "$glint" render "$1" --width "$2" --height "$3" --spp 16 --denoise -q -o "$tmp/16d.png"
  oiiotool "$tmp/16.png" "$tmp/16d.png" "$tmp/$4.png" --mosaic 3x1 -o "$5"
  rm -rf "$tmp"
  echo "$5"
}
denoise_strip scenes/cornell-box.yaml 256 256 1024 docs/images/denoise-cornell.png
# The issue's scene: pbrt-v4's features at 64 spp, the same denoised, and 256 spp (its right half).
denoise_tmp=$(mktemp -d)
"$glint" render scenes/pbrt/features.pbrt --spp 64 --denoise -q -o "$denoise_tmp/64d.exr"
"$glint" render scenes/pbrt/features.pbrt --spp 256 -q -o "$denoise_tmp/256.exr"
oiiotool "$denoise_tmp/64d.exr" --ch noisy.R,noisy.G,noisy.B --chnames R,G,B --cut 400x400+200+0 \
  "$denoise_tmp/64d.exr" --ch R,G,B --cut 400x400+200+0 "$denoise_tmp/256.exr" --ch R,G,B --cut 400x400+200+0 \
  --mosaic 3x1 --colorconvert linear sRGB --resize 900x300 -o docs/images/denoise-features.png
rm -rf "$denoise_tmp"
echo docs/images/denoise-features.png
# Texture edges through the denoiser: the path-traced textures scene, against 64 spp.
denoise_strip scenes/textures-lit.yaml 400 225 64 docs/images/denoise-textures.png
# Many lights (docs/lights.md): the town square of bench/many_lights.py at equal time (8 s each,
# 2 threads): the power sampler, the light BVH, and the BVH's 4096-spp reference.
lights_tmp=$(mktemp -d)
RUNS=1 OUT="$lights_tmp" bench/many_lights.sh "${1:-build}" > /dev/null
for f in power-1 bvh-1 ref-bvh; do
  oiiotool "$lights_tmp/$f.exr" --ch R,G,B --mulc 3 --colorconvert linear sRGB -o "$lights_tmp/$f.png"
done
oiiotool "$lights_tmp/power-1.png" "$lights_tmp/bvh-1.png" "$lights_tmp/ref-bvh.png" --mosaic 3x1 \
  -o docs/images/many-lights-equal-time.png
echo docs/images/many-lights-equal-time.png
# pbrt-v4's features at 256 spp, around the lamp: the power sampler, then the light BVH.
for s in power bvh; do
  "$glint" render scenes/pbrt/features.pbrt --spp 256 --light-sampler "$s" -q -o "$lights_tmp/features-$s.exr"
  oiiotool "$lights_tmp/features-$s.exr" --ch R,G,B --cut 380x200+80+160 --colorconvert linear sRGB \
    -o "$lights_tmp/features-$s.png"
done
oiiotool "$lights_tmp/features-power.png" "$lights_tmp/features-bvh.png" --mosaic 2x1 --resize 600x158 \
  -o docs/images/features-light-sampler.png
rm -rf "$lights_tmp"
echo docs/images/features-light-sampler.png
# Texture filtering (docs/textures.md): the receding floor at 1 spp unfiltered, 1 spp with EWA,
# and the pixels' means (1024 spp, unfiltered), stacked.
filter_tmp=$(mktemp -d)
"$glint" render scenes/texture-filtering.yaml --texture-filter none -q -o "$filter_tmp/none.png"
"$glint" render scenes/texture-filtering.yaml -q -o "$filter_tmp/ewa.png"
"$glint" render scenes/texture-filtering.yaml --texture-filter none --spp 1024 -q -o "$filter_tmp/ref.png"
oiiotool "$filter_tmp/none.png" "$filter_tmp/ewa.png" "$filter_tmp/ref.png" --mosaic 1x3 --resize 360x608 \
  -o docs/images/texture-filtering.png
rm -rf "$filter_tmp"
echo docs/images/texture-filtering.png
# The same floor in a chrome ball and through a glass ball (the offset rays carried through
# specular bounces): the balls' part of the frame, 1 spp unfiltered, 1 spp with EWA, 1024 spp.
filter_tmp=$(mktemp -d)
"$glint" render scenes/texture-filtering-mirrors.yaml --texture-filter none -q -o "$filter_tmp/none.png"
"$glint" render scenes/texture-filtering-mirrors.yaml -q -o "$filter_tmp/ewa.png"
"$glint" render scenes/texture-filtering-mirrors.yaml --texture-filter none --spp 1024 -q -o "$filter_tmp/ref.png"
oiiotool "$filter_tmp/none.png" --cut 340x150+70+45 "$filter_tmp/ewa.png" --cut 340x150+70+45 \
  "$filter_tmp/ref.png" --cut 340x150+70+45 --mosaic 1x3 -o docs/images/texture-filtering-mirrors.png
rm -rf "$filter_tmp"
echo docs/images/texture-filtering-mirrors.png
# Motion blur (docs/motion.md): the scene with its shutter closed and open, side by side.
motion_tmp=$(mktemp -d)
sed 's/  shutter: \[0, 1\]/  shutter: [0, 0]/' scenes/motion-blur.yaml > "$motion_tmp/still.yaml"
"$glint" render "$motion_tmp/still.yaml" -q -o "$motion_tmp/still.png"
"$glint" render scenes/motion-blur.yaml -q -o "$motion_tmp/blur.png"
oiiotool "$motion_tmp/still.png" "$motion_tmp/blur.png" --mosaic 2x1 --resize 723x203 -o docs/images/motion-blur.png
rm -rf "$motion_tmp"
echo docs/images/motion-blur.png
