#!/usr/bin/env bash
# Runs one fuzz target of a GLINT_FUZZ build (make fuzz) under its policy: ASan+UBSan (built in),
# 2 GB of memory (-rss_limit_mb; no single allocation above 1.2 GB: the harness gives scenes a
# 1 GB memory limit), 10 s per input; a crash,
# a sanitizer report, an uncaught exception, a slow input or running out of memory all fail.
#
#   fuzz/run.sh BUILD TARGET regression   every seed and fuzz/regressions/TARGET once, then a fixed
#                                         number of mutations from seed 1 ($GLINT_FUZZ_RUNS, or the
#                                         target's default below: a few seconds each)
#   fuzz/run.sh BUILD TARGET SECONDS      fuzz for SECONDS; new inputs kept in BUILD/fuzz/found/TARGET,
#                                         failures in BUILD/fuzz/artifacts/
set -euo pipefail
build=$(cd "$1" && pwd)
target=$2
mode=$3
src=$(cd "$(dirname "$0")" && pwd)
bin=$build/fuzz/fuzz_$target
seeds=$build/fuzz/corpus/$target
regressions=$src/regressions/$target
[[ -x $bin ]] || { echo "run.sh: no $bin: build it with 'make fuzz'" >&2; exit 2; }
[[ -d $seeds ]] || { echo "run.sh: no seed corpus $seeds: build it with 'make fuzz'" >&2; exit 2; }
mkdir -p "$regressions"
flags=(-rss_limit_mb=2048 -malloc_limit_mb=1200 -timeout=10 -max_len=65536 -print_final_stats=1)
[[ -f $src/dict/$target.dict ]] && flags+=(-dict="$src/dict/$target.dict")
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$src/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
if [[ $mode == regression ]]; then
  declare -A runs=([scene]=10000 [pbrt]=4000 [obj]=20000 [ply]=20000 [gltf]=10000 [image]=400 [checkpoint]=20000 [structure]=2000)
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  # The first folder receives what the run finds; a temporary one, so that the repository and the
  # seed corpus stay as they are. Failures are written there too and reported by libFuzzer.
  "$bin" "${flags[@]}" -seed=1 -runs="${GLINT_FUZZ_RUNS:-${runs[$target]}}" -artifact_prefix="$work/" \
    "$work" "$seeds" "$regressions"
  exit
fi
found=$build/fuzz/found/$target
mkdir -p "$found" "$build/fuzz/artifacts"
# Fork mode keeps fuzzing past a failure (each is written to the artifacts folder).
exec "$bin" "${flags[@]}" -max_total_time="$mode" -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 -artifact_prefix="$build/fuzz/artifacts/$target-" \
  "$found" "$seeds" "$regressions"
