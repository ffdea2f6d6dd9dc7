#!/usr/bin/env bash
# Animations across ranks: scenes/animation.yaml's 48 frames (640x360, 16 spp, Whitted), rendered
# by one process of one thread, one process of two threads, and `mpirun -np 2` ranks of one thread
# (whole frames: 48 frames >= 2 ranks); the runs alternate. Prints a Markdown table of the median
# whole-command times and the speed-ups against one thread, and checks that every frame of the
# distributed job equals the single process's.
#
#   bench/mpi_frames.sh [BUILD_DIR] [RUNS]
#   FRAMES=0:47 SPP=16 bench/mpi_frames.sh build 3
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
runs=${2:-3}
frames=${FRAMES:-0:47}
spp=${SPP:-16}
source bench/mpi_common.sh
args=(render scenes/animation.yaml --frames "$frames" --spp "$spp" -q)

# One run of "$@" into a fresh folder $1: prints the wall seconds.
run() {
  local dir=$1 t0 t1
  shift
  rm -rf "$dir" && mkdir -p "$dir"
  t0=$(date +%s.%N)
  "$@" -o "$dir/f_%02d.exr"
  t1=$(date +%s.%N)
  awk "BEGIN { print $t1 - $t0 }"
}

: >"$out/t1.txt"
: >"$out/t2.txt"
: >"$out/r2.txt"
for i in $(seq "$runs"); do
  run "$out/t1" "$glint" "${args[@]}" --threads 1 >>"$out/t1.txt"
  run "$out/t2" "$glint" "${args[@]}" --threads 2 >>"$out/t2.txt"
  run "$out/r2" mpirun -np 2 "$glint" "${args[@]}" --threads 1 >>"$out/r2.txt"
  for f in "$out"/t1/*.exr; do
    idiff -fail 0 -warn 0 -a "$f" "$out/r2/$(basename "$f")" >/dev/null ||
      { echo "$(basename "$f"): the 2-rank frame differs from the single process's" >&2; exit 1; }
  done
done

python3 - "$out" "$runs" "$frames" "$spp" <<'PY'
import statistics, sys
out, runs, frames, spp = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
med = {n: statistics.median(float(l) for l in open(f"{out}/{n}.txt") if l.strip()) for n in ("t1", "t2", "r2")}
print(f"scenes/animation.yaml frames {frames}, {spp} spp; whole command, median of {runs} runs, alternating; frames identical\n")
print("| 1 process, 1 thread (s) | 1 process, 2 threads (s) | its speed-up | 2 ranks of 1 thread (s) | speed-up |")
print("|---|---|---|---|---|")
t1, t2, r2 = med["t1"], med["t2"], med["r2"]
print(f"| {t1:.2f} | {t2:.2f} | {t1 / t2:.2f}x | {r2:.2f} | {t1 / r2:.2f}x |")
PY
