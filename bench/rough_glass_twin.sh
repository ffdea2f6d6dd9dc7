#!/usr/bin/env bash
# Does Cycles' twin of the materials scene render its rough glass sphere as glint does? The
# frosted sphere of scenes/materials.yaml alone over the ground, under a uniform sky
# (0.8, 0.85, 1), no lamp, only the window [600, 760) x [125, 295) around it: glint, and Cycles
# with the sphere as a 256 x 128 UV-sphere mesh (the twin's choice) and as a point sphere
# (bench/materials_cycles.py ONLY=frosted, frosted-points), all at SPP. Prints each image's mean
# and its RMSE and relative RMSE against glint's (and glint's with another seed: the noise
# floor). pbrt-v4 on the same BSDF: bench/pbrt/rough-glass.pbrt.
#
#   bench/rough_glass_twin.sh [BUILD_DIR] [SPP]     env: THREADS (2), OUT (keep the images)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
spp=${2:-1024}
threads=${THREADS:-2}
glint="$build/apps/glint/glint"
out=${OUT:-$(mktemp -d)}
mkdir -p "$out"
for tool in blender oiiotool; do
  command -v "$tool" >/dev/null || { echo "missing $tool: run GLINT_BENCH_DEPS=1 scripts/install-deps.sh" >&2; exit 1; }
done
[ -x "$glint" ] || { echo "missing $glint: run make build" >&2; exit 1; }
source bench/image_error.sh

# The scene's copy sits beside it, so that its sky map's path still resolves (unused here).
scene=$(mktemp scenes/.rough-glass-XXXXXX.yaml)
trap 'rm -f "$scene"' EXIT
sed -e 's/^film: {\(.*\)}$/film: {\1, crop_pixels: [600, 760, 125, 295]}/' \
    -e 's/^background:.*/background: {type: constant, color: [0.8, 0.85, 1]}/' \
    -e '/type: sphere, center: \[-3.6\|type: sphere, center: \[-1.8\|type: sphere, center: \[0, \|type: sphere, center: \[1.8\|type: disk/d' \
    scenes/materials.yaml > "$scene"
grep -q crop_pixels "$scene" && [ "$(grep -c 'type: sphere' "$scene")" = 1 ] || { echo "rough_glass_twin.sh: scenes/materials.yaml changed; mend the sed" >&2; exit 1; }

"$glint" render "$scene" -q --spp "$spp" --threads "$threads" -o "$out/glint.exr"
"$glint" render "$scene" -q --spp "$spp" --threads "$threads" --seed 7 -o "$out/glint-seed7.exr"  # the noise floor
for only in frosted frosted-points; do
  blender -b --factory-startup -P bench/materials_cycles.py -- "$out/cycles-$only.exr" "$spp" "$threads" 1 "$only" > "$out/cycles-$only.log" 2>&1 ||
    { echo "Cycles failed: $out/cycles-$only.log" >&2; exit 1; }
  # Blender's border gives one row more, at the bottom (171): keep glint's window.
  oiiotool "$out/cycles-$only.exr" --ch R,G,B --cut 160x170+0+0 -o "$out/cycles-$only.exr"
done

echo "The rough glass sphere alone, 160x170 window, $spp spp, $threads threads ($out)"
echo
echo "| image | mean | RMSE against glint | relative RMSE against glint |"
echo "|---|---|---|---|"
echo "| glint | $(mean_rgb "$out/glint.exr") | | |"
echo "| glint, another seed | $(mean_rgb "$out/glint-seed7.exr") | $(rmse "$out/glint-seed7.exr" "$out/glint.exr") | $(relative_rmse "$out/glint-seed7.exr" "$out/glint.exr") |"
for only in frosted frosted-points; do
  img="$out/cycles-$only.exr"
  echo "| Cycles, $([ "$only" = frosted ] && echo "UV-sphere mesh" || echo "point sphere") | $(mean_rgb "$img") | $(rmse "$img" "$out/glint.exr") | $(relative_rmse "$img" "$out/glint.exr") |"
done
