#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Sets up everything, builds sewerplan, and shows it on the paper's test environment (Fraunhofer AIS,
# Adria et al. 2004, section 6): the map, the paper's mission planned natively (the paper's plan,
# in its format) and checked by the independent validator, the paper-style ASCII database, a
# generated 100,000-manhole city with a 20-task mission, and last the paper's mission run on the
# simulated robot with an obstacle the head lift clears and one in the pipe it inspects: the
# recovery phases, the replan and the new route.
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
echo; echo "\$ sewerplan plan --map datasets/ais-testbed/map.json --mission datasets/ais-testbed/missions/paper.json -o $out/paper.plan"
$sp plan --map datasets/ais-testbed/map.json --mission datasets/ais-testbed/missions/paper.json -o "$out/paper.plan"
cat "$out/paper.plan"
echo; echo "\$ sewerplan check --map datasets/ais-testbed/map.json --mission datasets/ais-testbed/missions/paper.json $out/paper.plan"
$sp check --map datasets/ais-testbed/map.json --mission datasets/ais-testbed/missions/paper.json "$out/paper.plan"
echo; echo "\$ sewerplan convert datasets/ais-testbed/map.json $out/ais-testbed.sewer"
$sp convert datasets/ais-testbed/map.json "$out/ais-testbed.sewer"
sed -n '1,12p' "$out/ais-testbed.sewer"
echo "..."
echo; echo "\$ sewerplan generate --manholes 100000 --topology meshed --seed 2 -o $out/city.json --mission-tasks 20 --mission-out $out/city-mission.json"
$sp generate --manholes 100000 --topology meshed --seed 2 -o "$out/city.json" --mission-tasks 20 \
  --mission-out "$out/city-mission.json"
$sp info "$out/city.json"
echo; echo "\$ sewerplan plan --map $out/city.json --mission $out/city-mission.json -o $out/city.plan"
$sp plan --map "$out/city.json" --mission "$out/city-mission.json" -o "$out/city.plan"
$sp check --map "$out/city.json" --mission "$out/city-mission.json" "$out/city.plan"
echo; echo "\$ sewerplan simulate --map datasets/ais-testbed/map.json --mission datasets/ais-testbed/missions/paper.json --faults datasets/ais-testbed/faults/demo.json --log $out/events.jsonl"
$sp simulate --map datasets/ais-testbed/map.json --mission datasets/ais-testbed/missions/paper.json \
  --faults datasets/ais-testbed/faults/demo.json --log "$out/events.jsonl"
echo "(event log: $out/events.jsonl)"
