#!/usr/bin/env bash
# Every string literal of glint's pbrt reader (parameter names among them) that appears nowhere
# as a string literal in pbrt-v4's sources: each line printed is a name pbrt-v4 does not know, or
# a word of glint's own (a metal's name, a message). pbrt-v4's sources: `fetch github:mmp/pbrt-v4`,
# extracted as ../shared/peers/pbrt-v4-build.md says.
#
#   bench/check_pbrt_names.sh PBRT_V4_SOURCE_DIR
set -euo pipefail
cd "$(dirname "$0")/.."
src=${1:?usage: bench/check_pbrt_names.sh PBRT_V4_SOURCE_DIR}
ours=$(mktemp) theirs=$(mktemp)
trap 'rm -f "$ours" "$theirs"' EXIT
grep -ohE '"[A-Za-z][A-Za-z0-9_.]*"' src/glint/formats/pbrt*.cpp src/glint/formats/pbrt_parser.h | tr -d '"' | sort -u > "$ours"
grep -rhoE '"[A-Za-z][A-Za-z0-9_.]*"' "$src/src/pbrt" --include='*.cpp' --include='*.h' | tr -d '"' | sort -u > "$theirs"
comm -23 "$ours" "$theirs"
