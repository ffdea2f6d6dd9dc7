#!/usr/bin/env bash
# glint against POV-Ray 3.7 on the article's Figure 14 at 1920x1080, 1 sample per pixel,
# whole process against whole process (parse, render, write a PNG), with 1 and 2 threads,
# both measured in the same run by hyperfine. Prints a Markdown table of medians and ratios.
#
#   bench/compare_povray.sh [BUILD_DIR] [RUNS]
#   W=3840 H=2160 bench/compare_povray.sh build 5     # the 4K variant
#   GLINT=/path/to/other/glint ...                      # another glint binary
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
runs=${2:-7}
glint=${GLINT:-$build/apps/glint/glint}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

for tool in hyperfine povray python3; do
  command -v "$tool" >/dev/null || { echo "missing $tool: run GLINT_BENCH_DEPS=1 scripts/install-deps.sh" >&2; exit 1; }
done
[ -x "$glint" ] || { echo "missing $glint: run make build" >&2; exit 1; }

W=${W:-1920} H=${H:-1080}
for t in 1 2; do
  hyperfine --style basic --warmup 1 --runs "$runs" --export-json "$out/t$t.json" \
    -n "glint-$t" "$glint render scenes/seed/fig14-reflections.yaml --width $W --height $H --spp 1 --threads $t -q -o $out/glint.png" \
    -n "povray-$t" "povray bench/fig14.pov +W$W +H$H -A +WT$t +FN +O$out/pov.png -D -GA File_Gamma=1.0" \
    >&2
done

# Render-only times, as each program reports its own: glint's summary line, POV-Ray's Trace Time.
for t in 1 2; do
  for i in $(seq "$runs"); do
    "$glint" render scenes/seed/fig14-reflections.yaml --width $W --height $H --spp 1 --threads $t -o "$out/glint.png" 2>&1 |
      sed -n 's/^rendered .* in \([0-9.]*\) s.*/\1/p' >> "$out/glint-render-$t.txt"
    povray bench/fig14.pov +W$W +H$H -A +WT$t +FN +O"$out/pov.png" -D File_Gamma=1.0 2>&1 | tr '\r' '\n' |
      sed -n 's/.*Trace Time:.*(\([0-9.]*\) seconds).*/\1/p' >> "$out/pov-render-$t.txt"
  done
done

python3 - "$out" "$runs" <<'PY'
import json, statistics, sys, platform, subprocess
out, runs = sys.argv[1], sys.argv[2]
cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
import os
print(f"Figure 14, {os.environ.get('W', 1920)}x{os.environ.get('H', 1080)}, 1 spp, whole process; median of {runs} runs (hyperfine), {cpu}\n")
print("| threads | glint (s) | POV-Ray 3.7 (s) | POV-Ray / glint |")
print("|---|---|---|---|")
for t in (1, 2):
    res = {r["command"]: r for r in json.load(open(f"{out}/t{t}.json"))["results"]}
    g = statistics.median(res[f"glint-{t}"]["times"])
    p = statistics.median(res[f"povray-{t}"]["times"])
    print(f"| {t} | {g:.3f} | {p:.3f} | {p / g:.1f}x |")
print(f"\nRender only (glint's reported render time; POV-Ray's Trace Time), median of {runs} runs:\n")
print("| threads | glint (s) | POV-Ray 3.7 (s) | POV-Ray / glint |")
print("|---|---|---|---|")
for t in (1, 2):
    g = statistics.median(float(x) for x in open(f"{out}/glint-render-{t}.txt").read().split())
    p = statistics.median(float(x) for x in open(f"{out}/pov-render-{t}.txt").read().split())
    print(f"| {t} | {g:.3f} | {p:.3f} | {p / g:.1f}x |")
PY
