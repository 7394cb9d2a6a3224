#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the libFuzzer targets (fuzz/, clang with ASan and UBSan) in build/fuzz and runs each for a
# bounded time, starting from its seed corpus fuzz/corpus/<name>/ (read only: new inputs go to a
# temporary directory), as many side by side as there are cores. Fails on a crash, leak or sanitizer
# report (no new target starts after one); the input that caused it is left in <build>/artifacts/.
# SEWERPLAN_FUZZ_BUILD names a build tree to reuse.
#   bash scripts/fuzz.sh [SECONDS_PER_TARGET]   (default 20)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-20}
jobs=${SEWERPLAN_JOBS:-$(nproc)}

# A build tree configured with SEWERPLAN_FUZZ=ON may be reused (SEWERPLAN_FUZZ_BUILD); otherwise
# build/fuzz is configured for fuzzing alone.
build=${SEWERPLAN_FUZZ_BUILD:-build/fuzz}
if ! grep -qs '^SEWERPLAN_FUZZ:BOOL=ON' "$build/CMakeCache.txt"; then
  build=build/fuzz
  mkdir -p build
  CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug \
    -DCMAKE_CXX_FLAGS_DEBUG="-O1 -gline-tables-only" \
    -DSEWERPLAN_FUZZ=ON -DSEWERPLAN_SANITIZE=ON -DSEWERPLAN_BUILD_TESTS=OFF -DSEWERPLAN_BUILD_BENCH=OFF \
    > build/fuzz.configure.log
fi
targets=()
for source in fuzz/*_fuzz.cc; do
  name=$(basename "$source" _fuzz.cc)
  targets+=("$name")
done
cmake --build "$build" -j "$jobs" --target "${targets[@]/#/sewerplan_fuzz_}"

mkdir -p "$build/artifacts"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# One target for `seconds`; its report is printed whole when it ends, so that targets running side
# by side do not interleave their lines. A crash writes the failed marker and the log's tail.
fuzz_one() {
  local name=$1 status=0
  mkdir -p "$work/$name"
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$build/fuzz/sewerplan_fuzz_$name" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$build/artifacts/$name-" \
    "$work/$name" "fuzz/corpus/$name" > "$work/$name.log" 2>&1 || status=$?
  {
    echo "== fuzz $name (${seconds} s)"
    grep -E "^stat::(number_of_executed_units|new_units_added)" "$work/$name.log" || true
    if [ "$status" != 0 ]; then
      tail -n 60 "$work/$name.log"
      echo "fuzz $name: failed (input in $build/artifacts/)"
      touch "$work/failed"
    fi
  } > "$work/$name.report"
  cat "$work/$name.report"
}
# The targets run `jobs` at a time (each fuzzer uses one core).
running=0
for name in "${targets[@]}"; do
  [ -e "$work/failed" ] && break
  fuzz_one "$name" &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then
    wait -n || true
    running=$((running - 1))
  fi
done
wait
if [ -e "$work/failed" ]; then
  echo "fuzzing: a target failed (above)" >&2
  exit 1
fi
echo "== fuzzing: no crash in ${#targets[@]} targets"
