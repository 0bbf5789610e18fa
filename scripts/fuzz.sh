#!/usr/bin/env bash
# Runs each libFuzzer target of fuzz/ for SECONDS on a working copy of its
# seed corpus in BUILD_DIR/corpus/ (new entries stay there, never in the git
# tree) and prints one line per target. Exits 1 when any target fails; its
# crashing input is in BUILD_DIR/crashes/TARGET/ and its log in BUILD_DIR/logs/.
# Used by `make fuzz` (which builds the targets first).
#   scripts/fuzz.sh BUILD_DIR SECONDS
set -euo pipefail
cd "$(dirname "$0")/.."
build=$1
seconds=$2

# target  -max_len  dictionary
targets=(
  "scene 16384 fuzz/scene.dict"
  "nrrd 4096 fuzz/nrrd.dict"
  "nifti 4096 -"
  "metaimage 4096 fuzz/metaimage.dict"
  "nhdr 4096 fuzz/nhdr.dict"
  "gltf 65536 fuzz/gltf.dict"
  "dicom 4096 -"
)

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
failed=0
for entry in "${targets[@]}"; do
  read -r name max_len dict <<<"$entry"
  corpus=$build/corpus/$name
  crashes=$build/crashes/$name
  log=$build/logs/fuzz_$name.log
  mkdir -p "$corpus" "$crashes" "$(dirname "$log")"
  cp fuzz/corpus/$name/* "$corpus/"
  args=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len="$max_len"
        -print_final_stats=1 -artifact_prefix="$crashes/")
  [[ "$dict" != "-" ]] && args+=(-dict="$dict")
  status=0
  "$build/fuzz/fuzz_$name" "${args[@]}" "$corpus" >"$log" 2>&1 || status=$?

  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  speed=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
  cov=$(sed -n 's/.* cov: \([0-9]*\) .*/\1/p' "$log" | tail -1)
  size=$(find "$corpus" -type f | wc -l)
  summary="${runs:-?} runs (${speed:-?}/s), coverage ${cov:-?}, corpus $size inputs"
  if [[ $status -eq 0 ]]; then
    echo "fuzz_$name: ok, ${seconds} s: $summary"
  else
    failed=1
    artifact=$(sed -n 's/.*Test unit written to //p' "$log" | tail -1)
    echo "fuzz_$name: FAILED (exit $status): $summary"
    grep -m1 -E 'runtime error|what\(\)|ERROR: (AddressSanitizer|LeakSanitizer|libFuzzer)' "$log" |
      sed 's/^ */  /' || true
    echo "  input: ${artifact:-none written}; log: $log"
    echo "  replay: $build/fuzz/fuzz_$name ${artifact:-INPUT}"
  fi
done
exit $failed
