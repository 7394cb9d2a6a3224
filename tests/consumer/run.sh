#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs the build tree into a scratch prefix, builds tests/consumer against the installed
# package with find_package(sewerplan), and runs it on the AIS test environment; then the same
# built with `pkg-config --cflags --libs sewerplan` alone (sewerplan.pc); then the embedding
# example in examples/replanner. Each with an embedder's warnings as errors (-Wall -Wextra
# -Wpedantic -Wconversion): the public headers must not warn in a program that includes them.
# Usage: run.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
src=$2
work="$build/consumer-test"
strict="-Wall -Wextra -Wpedantic -Wconversion -Werror"
rm -rf "$work"
cmake --install "$build" --prefix "$work/prefix" > /dev/null
test -x "$work/prefix/bin/sewerplan"
test -f "$work/prefix/include/sewerplan/core/sewer_map.h"
cmake -S "$src/tests/consumer" -B "$work/build" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_CXX_FLAGS="$strict" > /dev/null
cmake --build "$work/build" > /dev/null
out=$("$work/build/consumer" "$src/datasets/ais-testbed/map.json")
echo "$out"
[ "$out" = "ais-testbed: 12 manholes, 14 pipes" ]
# pkg-config: the file beside the CMake package, relocated with the prefix (${pcfiledir}).
pc=$(find "$work/prefix" -name sewerplan.pc)
[ -n "$pc" ] || { echo "FAIL: no sewerplan.pc installed"; exit 1; }
[ "$(dirname "$(dirname "$pc")")" = "$(dirname "$(find "$work/prefix" -type d -name cmake -path '*/lib*/cmake')")" ] ||
  { echo "FAIL: $pc is not beside the CMake package"; exit 1; }
export PKG_CONFIG_PATH
PKG_CONFIG_PATH=$(dirname "$pc")
[ "$(pkg-config --modversion sewerplan)" = "$("$work/prefix/bin/sewerplan" --version | cut -d' ' -f2)" ]
# shellcheck disable=SC2046,SC2086
c++ -std=c++20 $strict "$src/tests/consumer/main.cc" $(pkg-config --cflags --libs sewerplan) \
  -o "$work/pc-consumer"
out=$("$work/pc-consumer" "$src/datasets/ais-testbed/map.json")
echo "pkg-config: $out"
[ "$out" = "ais-testbed: 12 manholes, 14 pipes" ]
# The embedding example (examples/replanner) builds against the same installed package and replans.
cmake -S "$src/examples/replanner" -B "$work/example" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_CXX_FLAGS="$strict" > /dev/null
cmake --build "$work/example" > /dev/null
example=$("$work/example/replanner_example" "$src/datasets/ais-testbed/map.json" \
  "$src/datasets/ais-testbed/missions/paper.json")
echo "$example"
grep -q "after \"blockage in P4 at " <<<"$example"
grep -q "dropped 'inspect': .*pipe P4 is blocked" <<<"$example"
