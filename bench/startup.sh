#!/usr/bin/env bash
# Start-up and small-job cost of the glint binary, whole process (hyperfine medians), peak memory
# (/usr/bin/time's maximum resident set), and the runtime closure (ldd: libraries and bytes).
#
#   bench/startup.sh [GLINT_BINARY] [RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
glint=${1:-build/apps/glint/glint}
runs=${2:-20}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for tool in hyperfine python3; do
  command -v "$tool" >/dev/null || { echo "missing $tool: run GLINT_BENCH_DEPS=1 scripts/install-deps.sh" >&2; exit 1; }
done
[ -x /usr/bin/time ] || { echo "missing /usr/bin/time (Debian package time)" >&2; exit 1; }

names=(version info-bunny render-64)
cmds=("$glint --version"
      "$glint info scenes/bunny.yaml"
      "$glint render scenes/seed/fig14-reflections.yaml --width 64 --height 64 -q -o $out/small.png")
args=()
for i in "${!names[@]}"; do args+=(-n "${names[$i]}" "${cmds[$i]}"); done
hyperfine --style basic --warmup 3 --runs "$runs" -N --export-json "$out/t.json" "${args[@]}" >&2

for i in "${!names[@]}"; do
  for _ in 1 2 3 4 5; do
    /usr/bin/time -f %M ${cmds[$i]} >/dev/null 2>>"$out/mem-${names[$i]}.txt" || true
  done
done

libs=$(ldd "$glint" | awk '/=>/{print $3} /^\t\/lib/{print $1}' | sort -u)
count=$(echo "$libs" | wc -l)
bytes=$(echo "$libs" | xargs -r readlink -f | sort -u | xargs -r du -cbL | tail -1 | cut -f1)
self=$(du -bL "$glint" | cut -f1)

python3 - "$out" "$count" "$bytes" "$self" "${names[@]}" <<'PY'
import json, statistics, sys
out, count, nbytes, self_bytes, names = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), sys.argv[5:]
res = {r["command"]: r for r in json.load(open(f"{out}/t.json"))["results"]}
print("| command | median (ms) | min (ms) | peak RSS (MB) |")
print("|---|---|---|---|")
for n in names:
    t = res[n]["times"]
    mem = [int(l.split()[-1]) for l in open(f"{out}/mem-{n}.txt") if l.strip() and l.split()[-1].isdigit()]
    print(f"| {n} | {1000 * statistics.median(t):.1f} | {1000 * min(t):.1f} | {statistics.median(mem) / 1024:.1f} |")
print(f"\nRuntime closure (ldd): {count} shared libraries, {nbytes / 1e6:.1f} MB; the binary itself {self_bytes / 1e6:.1f} MB")
PY
