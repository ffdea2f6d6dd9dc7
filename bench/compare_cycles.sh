#!/usr/bin/env bash
# glint against Blender Cycles (CPU) on the Cornell box at 512x512: the same scene
# (scenes/cornell-box.yaml and bench/cornell_cycles.py), same spp and threads, render times as
# each program reports them (glint's summary line; Cycles' render call, without Blender's
# start-up), medians of RUNS runs, glint and Cycles alternating. Then image error: each
# renderer's first 64-spp image against a reference, the mean of glint's and Cycles' images at
# REF_SPP, and glint's error at equal time (glint given the spp it can render in Cycles' 64-spp
# time). The error images use other seeds than the reference. Prints Markdown tables.
#
#   bench/compare_cycles.sh [BUILD_DIR] [RUNS]
#   env: SPPS="64 1024", THREADS="1 2", THREADS_HIGH (threads for spp >= 1024; default THREADS),
#        REF_SPP=1024, OUT (keep the images in this folder), REPORT_ONLY=1 (reuse OUT's runs),
#        EQUAL_THREADS=2 (whose 64-spp medians set the equal-time spp: a one-thread series with
#        EQUAL_THREADS=1 and the OUT of a two-thread one reuses its references),
#        SCENE=cornell (default) or bunny (scenes/bunny.yaml, the bunny in the box; Cycles' twin
#        from bench/cornell_cycles.py with CYCLES_SCENE=bunny) or materials (scenes/materials.yaml,
#        800x400; Cycles' twin from bench/materials_cycles.py, whose materials are Cycles' nearest
#        nodes, so each renderer's error is taken against its own REF_SPP image, not their mean)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
runs=${2:-3}
spps=${SPPS:-64 1024}
threads=${THREADS:-1 2}
threads_high=${THREADS_HIGH:-$threads}
ref_spp=${REF_SPP:-1024}
glint="$build/apps/glint/glint"
out=${OUT:-$(mktemp -d)}
mkdir -p "$out"

for tool in blender oiiotool python3; do
  command -v "$tool" >/dev/null || { echo "missing $tool: run GLINT_BENCH_DEPS=1 scripts/install-deps.sh" >&2; exit 1; }
done
[ -x "$glint" ] || { echo "missing $glint: run make build" >&2; exit 1; }

scene_name=${SCENE:-cornell}
twin=bench/cornell_cycles.py
case $scene_name in
  cornell) scene=scenes/cornell-box.yaml ;;
  bunny) scene=scenes/bunny.yaml ;;
  materials) scene=scenes/materials.yaml twin=bench/materials_cycles.py ;;
  *) echo "compare_cycles.sh: SCENE=$scene_name: cornell, bunny or materials" >&2; exit 1 ;;
esac
export CYCLES_SCENE=$scene_name
glint_run() {  # spp threads out.exr [seed] -> "seconds rays"
  "$glint" render "$scene" --spp "$1" --threads "$2" -o "$3" --seed "${4:-0}" 2>&1 |
    sed -n 's/^rendered .* in \([0-9.]*\) s: \([0-9]*\) rays.*/\1 \2/p'
}
cycles_run() {  # spp threads out.exr seed -> seconds
  blender -b --factory-startup -P "$twin" -- "$3" "$1" "$2" "$4" 2>&1 |
    sed -n 's/^cycles render seconds: \([0-9.]*\)/\1/p'
}

# REPORT_ONLY=1 with OUT set: skip the timed runs, redo the error analysis and the tables.
[ "${REPORT_ONLY:-0}" = 1 ] && spps=""
# A new set of timed runs replaces OUT's old ones (the medians are of this run's alone).
[ -n "$spps" ] && : > "$out/glint.txt" && : > "$out/cycles.txt"
for spp in $spps; do
  ts=$threads
  [ "$spp" -ge 1024 ] && ts=$threads_high
  for t in $ts; do
    n=$runs
    [ "$spp" -ge 1024 ] && n=1  # minutes per image: one run
    for i in $(seq "$n"); do
      echo "spp $spp threads $t run $i" >&2
      echo "$spp $t $(glint_run "$spp" "$t" "$out/glint-$spp-$t-$i.exr")" >> "$out/glint.txt"
      echo "$spp $t $(cycles_run "$spp" "$t" "$out/cycles-$spp-$t-$i.exr" "$i")" >> "$out/cycles.txt"
    done
  done
done

# The reference: glint and Cycles at REF_SPP (2 threads), averaged.
[ -f "$out/glint-$ref_spp-2-1.exr" ] || glint_run "$ref_spp" 2 "$out/glint-$ref_spp-2-1.exr" > /dev/null
[ -f "$out/cycles-$ref_spp-2-1.exr" ] || cycles_run "$ref_spp" 2 "$out/cycles-$ref_spp-2-1.exr" 1 > /dev/null
rgb() { oiiotool "$1" --ch R,G,B -o "$2"; }
rgb "$out/glint-$ref_spp-2-1.exr" "$out/ref-g.exr"
rgb "$out/cycles-$ref_spp-2-1.exr" "$out/ref-c.exr"
# The twins of the Cornell box and the bunny agree (their images' means within 0.3 %): both are
# measured against the mean of the two references. The materials scene's twin does not (Cycles'
# Principled BSDF is not glint's plastic or conductor): each against its own.
if [ "$scene_name" = materials ]; then
  ref_glint=$out/ref-g.exr ref_cycles=$out/ref-c.exr
else
  oiiotool "$out/ref-g.exr" "$out/ref-c.exr" --add --mulc 0.5 -o "$out/ref.exr"
  ref_glint=$out/ref.exr ref_cycles=$out/ref.exr
fi

# Equal time: the spp glint renders in Cycles' median 64-spp time on EQUAL_THREADS threads (the
# image is the same for any thread count, so it is rendered on 2).
equal_threads=${EQUAL_THREADS:-2}
equal_spp=$(python3 - "$out" "$equal_threads" <<'PY'
import statistics, sys
out, threads = sys.argv[1], sys.argv[2]
def med(name, col):
    rows = [l.split() for l in open(f"{out}/{name}.txt")]
    return statistics.median(float(r[col]) for r in rows if r[0] == "64" and r[1] == threads)
print(max(1, round(64 * med("cycles", 2) / med("glint", 2))))
PY
)
# The images whose error is measured must share no samples with the reference: Cycles' second
# run (seed 2; the reference used seed 1) and glint renders with seed 7 (the reference: seed 0).
glint_run 64 2 "$out/glint-error-64.exr" 7 > /dev/null
glint_run "$equal_spp" 2 "$out/glint-equal.exr" 7 > /dev/null
cycles_error="$out/cycles-64-2-2.exr"
[ -f "$cycles_error" ] || cycles_run 64 2 "$cycles_error" 2 > /dev/null

# Per-channel means of (x - ref)^2 and (x - ref)^2 / (ref^2 + 0.01), by oiiotool's arithmetic.
stats() { oiiotool "$1" --ch R,G,B "$2" --sub --dup --mul --printstats 2>&1 | sed -n 's/.*Stats Avg: \([0-9.e+-]*\) \([0-9.e+-]*\) \([0-9.e+-]*\).*/\1 \2 \3/p'
          oiiotool "$1" --ch R,G,B "$2" --sub --dup --mul "$2" --dup --mul --addc 0.01 --div --printstats 2>&1 | sed -n 's/.*Stats Avg: \([0-9.e+-]*\) \([0-9.e+-]*\) \([0-9.e+-]*\).*/\1 \2 \3/p'; }
{ echo "glint-64 $(stats "$out/glint-error-64.exr" "$ref_glint" | tr '\n' ' ')"
  echo "cycles-64 $(stats "$cycles_error" "$ref_cycles" | tr '\n' ' ')"
  echo "glint-equal $(stats "$out/glint-equal.exr" "$ref_glint" | tr '\n' ' ')"
  echo "glint-vs-cycles-ref $(stats "$out/ref-g.exr" "$out/ref-c.exr" | tr '\n' ' ')"
} > "$out/errors.txt"
mean() { oiiotool "$1" --printstats 2>&1 | sed -n 's/.*Stats Avg: \([0-9.e+-]*\) \([0-9.e+-]*\) \([0-9.e+-]*\).*/\1 \2 \3/p'; }
echo "$(mean "$out/ref-g.exr") $(mean "$out/ref-c.exr")" > "$out/means.txt"

python3 - "$out" "$ref_spp" "$equal_spp" "$scene_name" "$equal_threads" <<'PY'
import math, statistics, sys
out, ref_spp, equal_spp, scene_name, equal_threads = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4], sys.argv[5]
cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")

def rows(name):
    r = {}
    for line in open(f"{out}/{name}.txt"):
        p = line.split()
        r.setdefault((int(p[0]), int(p[1])), []).append([float(x) for x in p[2:]])
    return r

g, c = rows("glint"), rows("cycles")
width, height = (800, 400) if scene_name == "materials" else (512, 512)
pixels = width * height
title = {"cornell": "Cornell box", "bunny": "The bunny in the Cornell box", "materials": "The materials scene"}[scene_name]
print(f"{title} {width}x{height}, {cpu}; render time only (median of the runs; one run at 1024 spp)\n")
print("| spp | threads | glint (s) | Cycles (s) | Cycles / glint | glint Msamples/s | Cycles Msamples/s | glint Mrays/s |")
print("|---|---|---|---|---|---|---|---|")
for key in sorted(g):
    spp, t = key
    gs = statistics.median(x[0] for x in g[key])
    rays = statistics.median(x[1] for x in g[key])
    cs = statistics.median(x[0] for x in c[key])
    print(f"| {spp} | {t} | {gs:.2f} | {cs:.2f} | {cs / gs:.2f}x | {pixels * spp / gs / 1e6:.2f} | "
          f"{pixels * spp / cs / 1e6:.2f} | {rays / gs / 1e6:.2f} |")

errs = {l.split()[0]: [float(x) for x in l.split()[1:]] for l in open(f"{out}/errors.txt")}
against = ("each renderer's own" if scene_name == "materials" else "the mean of glint's and Cycles'")
print(f"\nError against the reference ({against} {ref_spp}-spp images), 2 threads: "
      "RMSE and relative RMSE (square root of the mean over pixels and RGB of (x - ref)^2 / "
      "(ref^2 + 0.01))\n")
print("| image | RMSE | relative RMSE |")
print("|---|---|---|")
labels = {"glint-64": "glint, 64 spp", "cycles-64": "Cycles, 64 spp",
          "glint-equal": f"glint, {equal_spp} spp (Cycles' 64-spp time, {equal_threads} thread{'s' if equal_threads != '1' else ''})",
          "glint-vs-cycles-ref": f"glint {ref_spp} spp against Cycles {ref_spp} spp"}
for key, label in labels.items():
    e = errs[key]
    print(f"| {label} | {math.sqrt(sum(e[:3]) / 3):.4f} | {math.sqrt(sum(e[3:]) / 3):.4f} |")
m = [float(x) for x in open(f"{out}/means.txt").read().split()]
print(f"\nImage means (R G B) at {ref_spp} spp: glint {m[0]:.5f} {m[1]:.5f} {m[2]:.5f}, "
      f"Cycles {m[3]:.5f} {m[4]:.5f} {m[5]:.5f}")
PY
