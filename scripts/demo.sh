#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Sets up everything, builds sewerplan, and shows it on the paper's test environment (Fraunhofer AIS,
# Adria et al. 2004, section 6): the map summary, the paper's mission validated against it, a
# conversion to the paper-style ASCII database, and a generated city-sized network.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo > /dev/null
cmake --build build/release -j "$(nproc)" --target sewerplan_cli
sp=build/release/bin/sewerplan
out=build/demo
mkdir -p "$out"

echo; echo "\$ sewerplan info datasets/ais-testbed/map.json"
$sp info datasets/ais-testbed/map.json
echo; echo "\$ sewerplan validate datasets/ais-testbed/map.json --mission datasets/ais-testbed/missions/paper.json"
$sp validate datasets/ais-testbed/map.json --mission datasets/ais-testbed/missions/paper.json
echo; echo "\$ sewerplan convert datasets/ais-testbed/map.json $out/ais-testbed.sewer"
$sp convert datasets/ais-testbed/map.json "$out/ais-testbed.sewer"
sed -n '1,12p' "$out/ais-testbed.sewer"
echo "..."
echo; echo "\$ sewerplan generate --manholes 10000 --topology meshed --seed 7 -o $out/city.json"
$sp generate --manholes 10000 --topology meshed --seed 7 -o "$out/city.json"
$sp info "$out/city.json"
