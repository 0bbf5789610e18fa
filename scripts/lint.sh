#!/usr/bin/env bash
# The checks a compiler does not make: no function in renderer/ or cli/ over
# 100 lines (clang-tidy's readability-function-size), so each stays one
# concern a reader can see at once. Takes the compile commands of a
# file-by-file build (make build-files). Exit 1 listing each offender.
set -euo pipefail
build=${1:?usage: scripts/lint.sh BUILD_DIR (a -DCUTAWAY_UNITY=OFF build)}
[[ -f "$build/compile_commands.json" ]] || { echo "lint: no $build/compile_commands.json" >&2; exit 2; }
jobs=$(nproc)
config='{CheckOptions: [{key: readability-function-size.LineThreshold, value: 100}]}'
report=$(git ls-files 'renderer/*.cpp' 'cli/*.cpp' |
  xargs -P "$jobs" -n 4 clang-tidy -p "$build" --quiet --checks='-*,readability-function-size' \
    --config="$config" 2>/dev/null | grep -A1 'readability-function-size' || true)
if [[ -n "$report" ]]; then
  echo "lint: functions over 100 lines:" >&2
  echo "$report" >&2
  exit 1
fi
echo "lint: no function over 100 lines in renderer/ or cli/"
