#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs the build tree into a scratch prefix, builds tests/consumer against the installed
# package with find_package(sewerplan), and runs it on the AIS test environment; then the same for
# the embedding example in examples/replanner.
# Usage: run.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
src=$2
work="$build/consumer-test"
rm -rf "$work"
cmake --install "$build" --prefix "$work/prefix" > /dev/null
test -x "$work/prefix/bin/sewerplan"
test -f "$work/prefix/include/sewerplan/core/sewer_map.h"
cmake -S "$src/tests/consumer" -B "$work/build" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" > /dev/null
cmake --build "$work/build" > /dev/null
out=$("$work/build/consumer" "$src/datasets/ais-testbed/map.json")
echo "$out"
[ "$out" = "ais-testbed: 12 manholes, 14 pipes" ]
# The embedding example (examples/replanner) builds against the same installed package and replans.
cmake -S "$src/examples/replanner" -B "$work/example" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" > /dev/null
cmake --build "$work/example" > /dev/null
example=$("$work/example/replanner_example" "$src/datasets/ais-testbed/map.json" \
  "$src/datasets/ais-testbed/missions/paper.json")
echo "$example"
grep -q "after \"blockage in P4 at " <<<"$example"
grep -q "dropped 'inspect': .*pipe P4 is blocked" <<<"$example"
