#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the concurrent tests with ThreadSanitizer (gcc) in build/tsan and runs them: the
# BackgroundReplan tests (a replan on its own thread, cancelled from another; tests/executor/
# background_replan_test.cc) and the ExecutorHalt tests (a mission halted from another thread while a
# job runs; tests/executor/halt_test.cc). Only their own test binary (sewerplan_concurrency_tests) and the
# libraries under it are built, without OMPL, so that it fits in scripts/test.sh.
# Fails on the first data race.
#   bash scripts/tsan.sh
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${SEWERPLAN_JOBS:-$(nproc)}
build=build/tsan
mkdir -p build
# -O1: the build is nearly all of this stage's time, and ThreadSanitizer finds the same races at
# -O1 as at -O2 (its documentation suggests -O1 or more).
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DCMAKE_CXX_FLAGS="-fsanitize=thread" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread" \
  -DSEWERPLAN_BUILD_BENCH=OFF -DSEWERPLAN_WITH_OMPL=OFF -DSEWERPLAN_FUZZ=OFF \
  > build/tsan.configure.log
cmake --build "$build" -j "$jobs" --target sewerplan_concurrency_tests
TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 \
  "$build/tests/sewerplan_concurrency_tests" --gtest_filter='BackgroundReplan.*:ExecutorHalt.*' --gtest_repeat=20 \
  --gtest_brief=1
echo "== ThreadSanitizer: no data race in the concurrent tests"
