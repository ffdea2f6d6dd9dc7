#!/usr/bin/env bash
# glint against Blender Cycles (CPU) on the volume scenes of bench/volumes/: `fog` (a
# homogeneous medium in an interface box) and `cloud` (scenes/volumes/cloud.vdb as a grid
# medium; in Cycles a Volume object from the same file). The same scene in both
# (bench/volumes/SCENE.yaml and bench/volume_cycles.py). Render times as each program reports
# them (glint's summary line; Cycles' render call without Blender's start-up), medians of RUNS
# runs at SPP samples per pixel, the two alternating. Then the error of each 64-spp image
# against a reference (glint at REF_SPP), glint's error at Cycles' 64-spp time, and the
# converged images' channel means (glint and Cycles at REF_SPP). Prints Markdown tables.
#
#   bench/compare_volumes.sh [BUILD_DIR] [SCENE: fog|cloud] [RUNS]
#   env: SPP=64, THREADS=2, REF_SPP=1024, STEP_RATE (Cycles' volume_step_rate, default 1),
#        OUT (keep the images in this folder)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
which=${2:-fog}
runs=${3:-3}
spp=${SPP:-64}
threads=${THREADS:-2}
ref_spp=${REF_SPP:-1024}
step_rate=${STEP_RATE:-1}
glint="$build/apps/glint/glint"
out=${OUT:-$(mktemp -d)}
mkdir -p "$out"
for tool in blender oiiotool python3; do
  command -v "$tool" >/dev/null || { echo "missing $tool: run GLINT_BENCH_DEPS=1 scripts/install-deps.sh" >&2; exit 1; }
done
[ -x "$glint" ] || { echo "missing $glint: run make build" >&2; exit 1; }
scene="bench/volumes/$which.yaml"

glint_run() {  # spp out.exr seed -> seconds
  "$glint" render "$scene" --spp "$1" --threads "$threads" -o "$2" --seed "$3" 2>&1 |
    sed -n 's/^rendered .* in \([0-9.]*\) s: .*/\1/p'
}
cycles_run() {  # spp out.exr seed -> seconds (the image mirrored to glint's view, RGB only)
  blender -b --factory-startup -P bench/volume_cycles.py -- "$which" "$2" "$1" "$threads" "$3" "$step_rate" 2>&1 |
    sed -n 's/^cycles render seconds: \([0-9.]*\)/\1/p'
  oiiotool "$2" --ch R,G,B --flop -o "$2"
}

: > "$out/times.txt"
for i in $(seq "$runs"); do
  echo "$which run $i" >&2
  echo "glint $(glint_run "$spp" "$out/glint-$i.exr" "$((10 + i))")" >> "$out/times.txt"
  echo "cycles $(cycles_run "$spp" "$out/cycles-$i.exr" "$((10 + i))")" >> "$out/times.txt"
done
echo "references" >&2
[ -f "$out/ref-glint.exr" ] || glint_run "$ref_spp" "$out/ref-glint.exr" 0 > /dev/null
[ -f "$out/ref-cycles.exr" ] || cycles_run "$ref_spp" "$out/ref-cycles.exr" 0 > /dev/null

read -r equal_spp < <(python3 - "$out" "$spp" <<'PY'
import statistics, sys
rows = [l.split() for l in open(f"{sys.argv[1]}/times.txt")]
med = lambda who: statistics.median(float(r[1]) for r in rows if r[0] == who)
print(max(1, round(int(sys.argv[2]) * med("cycles") / med("glint"))))
PY
)
glint_run "$equal_spp" "$out/glint-equal.exr" 99 > /dev/null

# Per-channel means of (x - ref)^2 and (x - ref)^2 / (ref^2 + 0.01), by oiiotool's arithmetic.
avg() { sed -n 's/.*Stats Avg: \([0-9.e+-]*\) \([0-9.e+-]*\) \([0-9.e+-]*\).*/\1 \2 \3/p'; }
err() { echo "$(oiiotool "$1" --ch R,G,B "$2" --ch R,G,B --sub --dup --mul --printstats 2>&1 | avg)" \
             "$(oiiotool "$1" --ch R,G,B "$2" --ch R,G,B --sub --dup --mul "$2" --ch R,G,B --dup --mul --addc 0.01 --div --printstats 2>&1 | avg)"; }
ref="$out/ref-glint.exr"
{ echo "glint-$spp $(err "$out/glint-1.exr" "$ref")"
  echo "cycles-$spp $(err "$out/cycles-1.exr" "$ref")"
  echo "glint-equal $(err "$out/glint-equal.exr" "$ref")"
  echo "cycles-ref $(err "$out/ref-cycles.exr" "$ref")"
} > "$out/errors.txt"
echo "$(oiiotool "$ref" --ch R,G,B --printstats 2>&1 | avg) $(oiiotool "$out/ref-cycles.exr" --ch R,G,B --printstats 2>&1 | avg)" > "$out/means.txt"

python3 - "$out" "$which" "$spp" "$threads" "$ref_spp" "$equal_spp" "$step_rate" <<'PY'
import math, statistics, sys
out, which, spp, threads, ref_spp, equal_spp, step = sys.argv[1:8]
rows = [l.split() for l in open(f"{out}/times.txt")]
t = {w: [float(r[1]) for r in rows if r[0] == w] for w in ("glint", "cycles")}
g, c = statistics.median(t["glint"]), statistics.median(t["cycles"])
print(f"**{which}**, {spp} spp, {threads} threads, Cycles volume_step_rate {step}: glint {g:.2f} s, "
      f"Cycles {c:.2f} s (medians of {len(t['glint'])}; runs {t['glint']} / {t['cycles']}), "
      f"Cycles / glint = {c / g:.2f}x\n")
print(f"| image (against glint at {ref_spp} spp) | RMSE | relative RMSE |")
print("|---|---|---|")
labels = {f"glint-{spp}": f"glint, {spp} spp", f"cycles-{spp}": f"Cycles, {spp} spp",
          "glint-equal": f"glint, {equal_spp} spp (Cycles' {spp}-spp time)",
          "cycles-ref": f"Cycles at {ref_spp} spp (bias + its noise)"}
for line in open(f"{out}/errors.txt"):
    k, *v = line.split()
    v = [float(x) for x in v]
    print(f"| {labels[k]} | {math.sqrt(sum(v[:3]) / 3):.4f} | {math.sqrt(sum(v[3:]) / 3):.4f} |")
m = [float(x) for x in open(f"{out}/means.txt").read().split()]
d = [100 * (m[3 + i] - m[i]) / m[i] for i in range(3)]
print(f"\nChannel means at {ref_spp} spp: glint {m[0]:.4f} {m[1]:.4f} {m[2]:.4f}, Cycles {m[3]:.4f} "
      f"{m[4]:.4f} {m[5]:.4f} (Cycles - glint: {d[0]:+.2f} %, {d[1]:+.2f} %, {d[2]:+.2f} %)")
PY
