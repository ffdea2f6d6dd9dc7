#!/usr/bin/env bash
# glint's BVH beside Embree 3 on the bunny in the Cornell box, the glTF test scene, a
# million-triangle mesh and its latitude-longitude variant (fans of slivers at the poles; both
# generated here by glint_make_mesh, not committed), with
# 1 and 2 threads: `glint bench --accel all` builds each backend (bvh, sbvh, embree) and traces the same primary and one-bounce
# diffuse rays, the backends taking turns round by round, reporting medians of RUNS rounds. Prints markdown
# tables (docs/benchmarks.md).
#
#   bench/compare_embree.sh [BUILD_DIR] [RUNS]        (defaults: build 5)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
runs=${2:-5}
glint="$build/apps/glint/glint"
out=${OUT:-/tmp/glint-embree-bench}
mkdir -p "$out"
[[ -f "$out/cube-1m.ply" ]] || "$build/tools/glint_make_mesh" "$out/cube-1m.ply" 289 cube
[[ -f "$out/latlong-1m.ply" ]] || "$build/tools/glint_make_mesh" "$out/latlong-1m.ply" 500 latlong
[[ -f "$out/gltf/textured.glb" ]] || python3 scripts/make_gltf_scene.py "$out/gltf" > /dev/null

echo "| scene | triangles | threads | backend | build (s) | memory | bytes/triangle | primary Mrays/s | diffuse Mrays/s |"
echo "|---|---|---|---|---|---|---|---|---|"
for scene in scenes/bunny.yaml "$out/gltf/textured.glb" "$out/cube-1m.ply" "$out/latlong-1m.ply"; do
  for threads in 1 2; do
    "$glint" bench "$scene" --accel all --threads "$threads" --runs "$runs" --width 640 --height 480 > "$out/run.txt" 2>/dev/null
    tris=$(head -1 "$out/run.txt" | sed -E 's/.*: ([0-9]+) triangles.*/\1/')
    grep -E "^(bvh|sbvh|embree) " "$out/run.txt" | while read -r backend build_s mem unit bpt prim diff _; do
      echo "| $(basename "$scene") | $tris | $threads | $backend | $build_s | $mem $unit | $bpt | $prim | $diff |"
    done
  done
done
