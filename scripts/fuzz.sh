#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the libFuzzer targets (fuzz/, clang with ASan and UBSan) in build/fuzz and runs each for a
# bounded time, starting from its seed corpus fuzz/corpus/<name>/ (read only: new inputs go to a
# temporary directory). Fails on the first crash, leak or sanitizer report; the input that caused
# it is left in <build>/artifacts/. SEWERPLAN_FUZZ_BUILD names a build tree to reuse.
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
for name in "${targets[@]}"; do
  echo "== fuzz $name (${seconds} s)"
  mkdir -p "$work/$name"
  status=0
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$build/fuzz/sewerplan_fuzz_$name" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$build/artifacts/$name-" \
    "$work/$name" "fuzz/corpus/$name" > "$work/$name.log" 2>&1 || status=$?
  grep -E "^stat::(number_of_executed_units|new_units_added)" "$work/$name.log" || true
  if [ "$status" != 0 ]; then
    tail -n 60 "$work/$name.log" >&2
    echo "fuzz $name: failed (input in $build/artifacts/)" >&2
    exit 1
  fi
done
echo "== fuzzing: no crash in ${#targets[@]} targets"
