#!/usr/bin/env bash
# Two glint binaries (before and after a change that must not change any image) render every
# scene in scenes/ (64x48, 4 spp) and the command line's other paths (the demo, PNG output, one
# thread, adaptive sampling, an animation, checkpoint and resume, a pbrt-v4 killeroo, the bunny
# PLY directly, a glTF, info, convert, five errors, and a 2-rank MPI render); then every image is
# compared pixel for pixel (idiff, no tolerance) and every message and exit status as text (with
# times and rates masked). Prints the differences, or "ALL SAME (N files)".
#
#   bench/ab_images.sh A_BINARY B_BINARY [WORK_DIR]
set -uo pipefail
if [[ $# -lt 2 ]]; then sed -n '2,8p' "$0"; exit 2; fi
a=$(realpath "$1") b=$(realpath "$2") work=${3:-$(mktemp -d)}
cd "$(dirname "$0")/.."
models=${GLINT_MODEL_PATH:-../shared/models}
root=""; [[ $(id -u) == 0 ]] && root=--allow-run-as-root

capture() {
  local G=$1 O=$2 S="--width 64 --height 48 --spp 4"
  mkdir -p "$O/conv" "$O/conv2"
  run() { local name=$1; shift; "$@" >"$O/$name.out" 2>"$O/$name.err"; echo $? >"$O/$name.rc";
          sed -i "s#$O#OUT#g" "$O/$name.out" "$O/$name.err"; }
  for s in scenes/seed/*.yaml scenes/*.yaml scenes/volumes/*.yaml scenes/pbrt/*.pbrt scenes/textures/uv-grid.yaml; do
    n=$(echo "$s" | tr '/' '_'); run "r_$n" "$G" render "$s" $S -o "$O/$n.exr"
  done
  run aov "$G" render scenes/cornell-box.yaml $S --aovs -o "$O/aov.exr"
  run demo "$G" render -q -o "$O/demo.png"
  run png "$G" render scenes/seed/fig14-reflections.yaml -o "$O/fig14.png"
  run t1 "$G" render scenes/cornell-box.yaml $S --threads 1 -o "$O/t1.exr"
  run adapt "$G" render scenes/cornell-box.yaml $S --noise-threshold 0.05 -o "$O/adapt.exr"
  run anim "$G" render scenes/animation.yaml --width 32 --height 24 --spp 2 --frames 0:3 -o "$O/anim_%04d.exr"
  run ckpt "$G" render scenes/cornell-box.yaml $S --checkpoint "$O/ck.glintckpt" -o "$O/ck.exr"
  run resume "$G" render scenes/cornell-box.yaml $S --resume "$O/ck.glintckpt" -o "$O/ck2.exr"
  run kill "$G" render "$models/pbrt-v4-scenes/killeroos/killeroo-simple.pbrt" $S -o "$O/kill.exr"
  run bunnyply "$G" render "$models/stanford-bunny.ply" $S -o "$O/bunny_ply.exr"
  run info1 "$G" info scenes/cornell-box.yaml
  run info2 "$G" info scenes/pbrt/materials.pbrt
  run info3 "$G" info scenes/bunny.yaml
  run conv "$G" convert scenes/pbrt/features.pbrt -o "$O/conv/features.yaml"
  run conv2 "$G" convert scenes/materials.yaml -o "$O/conv2/m.yaml"
  run bad1 "$G" render /nonexistent.yaml
  run bad2 "$G" render scenes/seed/fig07-sphere.yaml --width -3
  run bad3 "$G" render README.md
  run bad4 "$G" render scenes/cornell-box.yaml -o "$O/x.bmp"
  run bad5 "$G" info nothing.pbrt
  local d; d=$(mktemp -d)
  python3 scripts/make_gltf_scene.py "$d" > /dev/null && run gltf "$G" render "$d/textured.glb" $S -o "$O/gltf.exr"
  rm -rf "$d"
  command -v mpirun > /dev/null && run mpi mpirun $root --oversubscribe -np 2 "$G" render scenes/cornell-box.yaml $S -q -o "$O/mpi.exr"
}

capture "$a" "$work/a"
capture "$b" "$work/b"
mask() { sed -E 's/[0-9]+(\.[0-9]+)? ?(s|ms|µs|MB|Mrays\/s|%)\b/N/g' "$1"; }
bad=0
for f in $(cd "$work/a" && find . -type f | sort); do
  case $f in
    *.out|*.err) diff -q <(mask "$work/a/$f") <(mask "$work/b/$f") > /dev/null || { echo "TEXT DIFF $f"; bad=1; } ;;
    *.exr|*.png) idiff -q -fail 0 -failpercent 0 -warn 0 -a "$work/a/$f" "$work/b/$f" > /dev/null 2>&1 || { echo "PIXELS DIFF $f"; bad=1; } ;;
    *.glintckpt|*.vdb) ;;  # they hold the render time
    *) cmp -s "$work/a/$f" "$work/b/$f" || { echo "DIFF $f"; bad=1; } ;;
  esac
done
[[ $bad == 0 ]] && echo "ALL SAME ($(cd "$work/a" && find . -type f | wc -l) files)"
exit $bad
