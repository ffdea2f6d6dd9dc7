#!/usr/bin/env bash
# Many lights: the light BVH against the power sampler on bench/many_lights.py's town square
# (1,024 lamps), at equal time. References: REF_SPP samples with each sampler (other seeds); the
# error of every image is measured against the BVH's reference, and the two references' means
# are compared (the samplers must converge to the same image). Each equal-time render is given
# --time SECONDS and RUNS seeds; the table shows the medians. Prints a Markdown table.
#
#   bench/many_lights.sh [BUILD_DIR]
#   env: WIDTH=240 HEIGHT=135, SECONDS_EACH=8, RUNS=3, REF_SPP=4096, THREADS=2, OUT (keep images)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
width=${WIDTH:-240}
height=${HEIGHT:-135}
seconds=${SECONDS_EACH:-8}
runs=${RUNS:-3}
ref_spp=${REF_SPP:-4096}
threads=${THREADS:-2}
glint="$build/apps/glint/glint"
out=${OUT:-$(mktemp -d)}
mkdir -p "$out"
command -v oiiotool >/dev/null || { echo "missing oiiotool: run GLINT_BENCH_DEPS=1 scripts/install-deps.sh" >&2; exit 1; }
. bench/image_error.sh
scene="$out/many-lights.yaml"
/usr/bin/python3 bench/many_lights.py > "$scene"

glint_run() {  # out.exr flags... -> "seconds spp-summary"
  local o=$1; shift
  "$glint" render "$scene" --width "$width" --height "$height" --threads "$threads" -o "$o" "$@" 2>&1 |
    sed -n 's/^rendered [0-9x]* at \(.*\) in \([0-9.]*\) s: .*/\2 \1/p'
}
mean_of() {  # image -> mean over pixels and channels
  oiiotool "$1" --ch R,G,B --printstats 2>&1 | sed -n 's/.*Stats Avg: \([0-9.e+-]*\) \([0-9.e+-]*\) \([0-9.e+-]*\).*/\1 \2 \3/p' |
    awk '{printf "%.5f", ($1 + $2 + $3) / 3}'
}
median() { sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }

for s in bvh power; do
  echo "reference, $s, $ref_spp spp" >&2
  glint_run "$out/ref-$s.exr" --spp "$ref_spp" --seed 1000 --light-sampler "$s" >&2
done
echo "| light sampler | samples in ${seconds} s (median of $runs) | relative RMSE (median) | relative MSE / power's |"
echo "|---|---:|---:|---:|"
declare -A mse
for s in power bvh; do
  errs=() spps=()
  for r in $(seq 1 "$runs"); do
    read -r t what < <(glint_run "$out/$s-$r.exr" --spp 100000 --seed "$r" --time "${seconds}s" --light-sampler "$s")
    spps+=("$(echo "$what" | sed -n 's/^\([0-9]*\) spp.*/\1/p')")
    errs+=("$(relative_rmse "$out/$s-$r.exr" "$out/ref-bvh.exr")")
  done
  e=$(printf '%s\n' "${errs[@]}" | median)
  n=$(printf '%s\n' "${spps[@]}" | median)
  mse[$s]=$(awk -v e="$e" 'BEGIN {print e * e}')
  ratio=$(awk -v a="${mse[$s]}" -v b="${mse[power]}" 'BEGIN {printf "%.3f", a / b}')
  echo "| $s | $n | $e | $ratio |"
done
mb=$(mean_of "$out/ref-bvh.exr"); mp=$(mean_of "$out/ref-power.exr")
echo
echo "Reference means ($ref_spp spp): bvh $mb, power $mp, difference $(awk -v a="$mb" -v b="$mp" 'BEGIN {printf "%.2f", 100 * (a - b) / b}') %"
echo "Images in $out"
