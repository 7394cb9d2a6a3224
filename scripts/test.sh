#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Sets up everything and runs every test, on a fresh Debian 12 machine:
#   1. installs the Debian packages sewerplan needs (scripts/install-deps.sh, skips what is present);
#   2. checks the code style (clang-format);
#   3. builds with warnings as errors, with the Python module (SEWERPLAN_PYTHON), and runs the whole
#      suite (unit, CLI and its --json, pytest and the Python example, install: the CMake package
#      and the Debian package in a scratch root, layering);
#   4. builds with clang, AddressSanitizer and UndefinedBehaviorSanitizer and runs the suite again;
#      the libFuzzer targets are built in the same tree;
#   5. builds the concurrent tests with ThreadSanitizer and runs them (scripts/tsan.sh);
#   6. fuzzes every parser for a short time (scripts/fuzz.sh in the ASan tree, 6 s per target; longer runs: scripts/fuzz.sh SECONDS).
# Each stage prints its wall time, so the CI budget (45 minutes) can be watched stage by stage.
# Build trees go to build/release, build/asan and build/tsan (build/fuzz if step 4 is skipped). Set
# SEWERPLAN_SKIP_ASAN=1 to skip step 4 locally, SEWERPLAN_SKIP_TSAN=1 step 5, SEWERPLAN_SKIP_FUZZ=1
# step 6 (SEWERPLAN_FUZZ_SECONDS sets its time).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
# Prints how long the stage that just ended took (bash counts SECONDS from the start).
stage_start=0
stage_done() {
  echo "== $1: $((SECONDS - stage_start)) s (total $((SECONDS / 60)) min $((SECONDS % 60)) s)"
  stage_start=$SECONDS
}

bash scripts/install-deps.sh
stage_done "dependencies"

echo "== style: clang-format"
bash scripts/check-format.sh
stage_done "style"

# The trees are built from scratch, so their debug information is cut to line tables (-g1,
# -gline-tables-only): sanitizer reports and backtraces still name file and line, and a file
# compiles in about a quarter less time.
echo "== release build and tests"
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSEWERPLAN_PYTHON=ON \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG"
cmake --build build/release -j "$jobs"
ctest --test-dir build/release --output-on-failure -j "$jobs"
stage_done "release build and tests"

if [ "${SEWERPLAN_SKIP_ASAN:-0}" != 1 ]; then
  echo "== ASan + UBSan build and tests (clang)"
  # The fuzz targets share this tree: the libraries compile once, those the parsers live in with
  # coverage feedback (fuzz/CMakeLists.txt), which leaves the planner's hot loops uninstrumented.
  CXX=clang++ cmake -S . -B build/asan -G Ninja -DCMAKE_BUILD_TYPE=Debug \
    -DCMAKE_CXX_FLAGS_DEBUG="-O1 -gline-tables-only" -DSEWERPLAN_SANITIZE=ON \
    -DSEWERPLAN_BUILD_BENCH=OFF -DSEWERPLAN_FUZZ=$([ "${SEWERPLAN_SKIP_FUZZ:-0}" = 1 ] && echo OFF || echo ON)
  cmake --build build/asan -j "$jobs"
  # Left to the release tree: what runs no compiled code of ours (the layering check of the sources,
  # the page's JavaScript tests) and the 10,000-manhole sweep of every search algorithm (72 s under
  # ASan; the same code paths run on the smaller and larger networks of that suite here).
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp" \
    ctest --test-dir build/asan --output-on-failure -j "$jobs" \
    -E '^(layering|web\.lod)$|EveryAlgorithmPlansValidly/10000_manholes_'
  stage_done "ASan + UBSan build and tests"
fi
if [ "${SEWERPLAN_SKIP_TSAN:-0}" != 1 ]; then
  echo "== ThreadSanitizer: the concurrent tests (gcc)"
  bash scripts/tsan.sh
  stage_done "ThreadSanitizer"
fi
if [ "${SEWERPLAN_SKIP_FUZZ:-0}" != 1 ]; then
  echo "== libFuzzer on every parser (clang)"
  # The targets were built with the ASan tree; without it fuzz.sh builds a tree of its own.
  SEWERPLAN_FUZZ_BUILD=build/asan bash scripts/fuzz.sh "${SEWERPLAN_FUZZ_SECONDS:-6}"
  stage_done "fuzzing"
fi
echo "== all tests passed"
