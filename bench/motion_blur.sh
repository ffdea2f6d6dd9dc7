#!/usr/bin/env bash
# What motion blur costs where nothing moves: render times (medians of RUNS) of still scenes by
# a glint built before motion blur (BASE, e.g. a clone of cd18062 built by bench/ab_builds.sh or
# .ci/run) and by this one, with and without a shutter; and the cost of blur itself on
# scenes/motion-blur.yaml (shutter open against [0, 0]). Prints Markdown tables.
#
#   bench/motion_blur.sh BASE_GLINT [BUILD_DIR]
#   env: RUNS=5, THREADS=2, SPP=16
set -euo pipefail
cd "$(dirname "$0")/.."
base=$1
build=${2:-build}
runs=${RUNS:-5}
threads=${THREADS:-2}
spp=${SPP:-16}
glint="$build/apps/glint/glint"
tmp=$(mktemp -d)
median() { sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }
seconds() {  # binary scene flags... -> median render seconds
  local bin=$1 scene=$2; shift 2
  for r in $(seq 1 "$runs"); do
    "$bin" render "$scene" --threads "$threads" --spp "$spp" -o "$tmp/t.exr" "$@" 2>&1 |
      sed -n 's/^rendered .* in \([0-9.]*\) s: .*/\1/p'
  done | median
}
# A still scene with a shutter: the same file with `shutter: [0, 1]` added to its camera.
with_shutter() { sed -e 's/^camera: {\(.*\)}$/camera: {\1, shutter: [0, 1]}/' -e 's/^camera:$/camera:\n  shutter: [0, 1]/' "$1" > "$2"; }
echo "| scene | before (s) | now (s) | now, shutter open (s) | now / before | shutter / before |"
echo "|---|---:|---:|---:|---:|---:|"
for scene in scenes/cornell-box.yaml scenes/materials.yaml scenes/bunny.yaml; do
  shuttered="$(dirname "$scene")/.motion-bench.yaml"  # beside it: its relative paths hold
  with_shutter "$scene" "$shuttered"
  a=$(seconds "$base" "$scene")
  b=$(seconds "$glint" "$scene")
  c=$(seconds "$glint" "$shuttered")
  rm -f "$shuttered"
  echo "| $scene | $a | $b | $c | $(awk -v x="$b" -v y="$a" 'BEGIN {printf "%.3f", x / y}') | $(awk -v x="$c" -v y="$a" 'BEGIN {printf "%.3f", x / y}') |"
done
echo
sed 's/  shutter: \[0, 1\]/  shutter: [0, 0]/' scenes/motion-blur.yaml > "$tmp/still.yaml"
s=$(seconds "$glint" "$tmp/still.yaml")
m=$(seconds "$glint" scenes/motion-blur.yaml)
echo "| scenes/motion-blur.yaml | shutter [0, 0] (s) | shutter [0, 1] (s) | ratio |"
echo "|---|---:|---:|---:|"
echo "| $spp spp | $s | $m | $(awk -v x="$m" -v y="$s" 'BEGIN {printf "%.3f", x / y}') |"
rm -rf "$tmp"
