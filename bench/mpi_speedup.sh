#!/usr/bin/env bash
# Distributed rendering's speed-up on this machine: the Cornell box and the bunny at 512x512 by the
# path tracer, one process of one thread against `mpirun -np 2` ranks of one thread, and, for
# what the machine's two cores give at all, one process of two threads; the runs alternate.
# Prints a Markdown table of medians (the render time glint reports, and the whole process) and
# the speed-ups; checks that every distributed image equals the single process's.
#
#   bench/mpi_speedup.sh [BUILD_DIR] [RUNS]
#   SPP=256 bench/mpi_speedup.sh build 3      # the issue's setting (about 20 minutes)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
runs=${2:-3}
spp=${SPP:-256}
source bench/mpi_common.sh

# One run: prints "render_seconds wall_seconds".
run() {
  local t0 t1 log
  t0=$(date +%s.%N)
  log=$("$@" 2>&1)
  t1=$(date +%s.%N)
  echo "$(sed -n 's/^rendered .* in \([0-9.]*\) s.*/\1/p' <<<"$log") $(awk "BEGIN { print $t1 - $t0 }")"
}

for scene in cornell-box bunny; do
  args=(render "scenes/$scene.yaml" --width 512 --height 512 --spp "$spp")
  : >"$out/$scene-1.txt"
  : >"$out/$scene-2.txt"
  : >"$out/$scene-t2.txt"
  for i in $(seq "$runs"); do
    run "$glint" "${args[@]}" --threads 1 -o "$out/$scene-1.exr" >>"$out/$scene-1.txt"
    run "$glint" "${args[@]}" --threads 2 -o "$out/$scene-t2.exr" >>"$out/$scene-t2.txt"
    run mpirun -np 2 "$glint" "${args[@]}" --threads 1 -o "$out/$scene-2.exr" >>"$out/$scene-2.txt"
    idiff -fail 0 -warn 0 -a "$out/$scene-1.exr" "$out/$scene-2.exr" >/dev/null ||
      { echo "$scene: the 2-rank image differs from the single process's" >&2; exit 1; }
  done
done

python3 - "$out" "$runs" "$spp" <<'PY'
import statistics, sys
out, runs, spp = sys.argv[1], int(sys.argv[2]), sys.argv[3]
print(f"512x512, {spp} spp, path tracer; median of {runs} runs, alternating; images identical\n")
print("| scene | 1 process, 1 thread (s) | 2 ranks of 1 thread (s) | speed-up | whole process, speed-up | 1 process, 2 threads (s) | its speed-up |")
print("|---|---|---|---|---|---|---|")
for scene in ("cornell-box", "bunny"):
    cols = []
    for n in ("1", "2", "t2"):
        rows = [list(map(float, l.split())) for l in open(f"{out}/{scene}-{n}.txt") if l.strip()]
        cols.append((statistics.median(r[0] for r in rows), statistics.median(r[1] for r in rows)))
    (r1, w1), (r2, w2), (t2, _) = cols
    print(f"| {scene} | {r1:.2f} | {r2:.2f} | {r1 / r2:.2f}x | {w1 / w2:.2f}x | {t2:.2f} | {r1 / t2:.2f}x |")
PY
