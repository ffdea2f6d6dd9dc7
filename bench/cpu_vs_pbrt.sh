#!/usr/bin/env bash
# CPU time of glint and of pbrt-v4 itself on one .pbrt file (issue 37's "≥ 5× less CPU time than
# pbrt-v4 on the Cornell box at 64 spp"): both render the file as it is (its film, sampler and
# integrator; --spp SPP for both when given) on THREADS threads, alternating, RUNS times each;
# user + system seconds of the whole process (start-up, parsing and the image file included) by
# /usr/bin/time. Prints each run and the medians, and the ratio pbrt-v4 / glint.
# pbrt-v4 is not a Debian package: build it with ../shared/peers/pbrt-v4-build.md.
#
#   PBRT=/path/to/pbrt bench/cpu_vs_pbrt.sh [BUILD_DIR] [SCENE.pbrt] [SPP] [RUNS]
#   defaults: build scenes/pbrt/cornell-box.pbrt (the file's 64 spp) 3; env THREADS (2)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
scene=${2:-scenes/pbrt/cornell-box.pbrt}
spp=${3:-}
runs=${4:-3}
threads=${THREADS:-2}
glint="$build/apps/glint/glint"
pbrt=${PBRT:?set PBRT to a pbrt-v4 binary (../shared/peers/pbrt-v4-build.md)}
[ -x "$glint" ] || { echo "missing $glint: run make build" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "missing /usr/bin/time: GLINT_BENCH_DEPS=1 scripts/install-deps.sh" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

cpu() {  # command... -> "cpu_seconds wall_seconds"
  /usr/bin/time -f "%U %S %e" -o "$out/t" "$@" >/dev/null 2>&1
  awk '{printf "%.2f %.2f\n", $1 + $2, $3}' "$out/t"
}
spp_glint=() spp_pbrt=()
if [ -n "$spp" ]; then spp_glint=(--spp "$spp"); spp_pbrt=(--spp "$spp"); fi
g=() p=()
for i in $(seq "$runs"); do
  read -r gc gw < <(cpu "$glint" render "$scene" "${spp_glint[@]}" --threads "$threads" -o "$out/g.exr")
  read -r pc pw < <(cpu "$pbrt" "${spp_pbrt[@]}" --nthreads "$threads" --outfile "$out/p.exr" "$scene")
  echo "run $i: glint ${gc} CPU-s (${gw} s), pbrt-v4 ${pc} CPU-s (${pw} s)"
  g+=("$gc") p+=("$pc")
done
median() { printf '%s\n' "$@" | sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
mg=$(median "${g[@]}") mp=$(median "${p[@]}")
echo "median CPU seconds: glint $mg, pbrt-v4 $mp; pbrt-v4 / glint = $(awk -v a="$mp" -v b="$mg" 'BEGIN {printf "%.2f", a / b}')"
