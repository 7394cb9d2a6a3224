#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Sets up everything, builds sewerplan, and shows it on the paper's test environment (Fraunhofer AIS,
# Adria et al. 2004, section 6): the map, the paper's mission planned natively (the paper's plan,
# in its format) and checked by the independent validator, the paper-style ASCII database, a
# generated 100,000-manhole city with a 20-task mission, and last the paper's mission run on the
# simulated robot with an obstacle the head lift clears and one in the pipe it inspects: the
# recovery phases, the replan and the new route. Then the same run drawn as SVG, the same mission
# over a CAN bus (SLCAN through a pseudo-terminal to a simulated controller node), the manhole
# passages planned with OMPL and used by the planner, and a 500-run fault campaign against the
# clairvoyant oracle and the paper-era baseline.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo > /dev/null
cmake --build build/release -j "$(nproc)" --target sewerplan_cli
sp=build/release/bin/sewerplan
out=build/demo
mkdir -p "$out"

echo; echo "\$ sewerplan info --map datasets/ais-testbed/map.json"
$sp info --map datasets/ais-testbed/map.json
echo; echo "\$ sewerplan validate --map datasets/ais-testbed/map.json --mission datasets/ais-testbed/missions/paper.json"
$sp validate --map datasets/ais-testbed/map.json --mission datasets/ais-testbed/missions/paper.json
echo; echo "\$ sewerplan plan --map datasets/ais-testbed/map.json --mission datasets/ais-testbed/missions/paper.json -o $out/paper.plan"
$sp plan --map datasets/ais-testbed/map.json --mission datasets/ais-testbed/missions/paper.json -o "$out/paper.plan"
cat "$out/paper.plan"
echo; echo "\$ sewerplan check --map datasets/ais-testbed/map.json --mission datasets/ais-testbed/missions/paper.json $out/paper.plan"
$sp check --map datasets/ais-testbed/map.json --mission datasets/ais-testbed/missions/paper.json "$out/paper.plan"
echo; echo "\$ sewerplan convert --map datasets/ais-testbed/map.json -o $out/ais-testbed.sewer"
$sp convert --map datasets/ais-testbed/map.json -o "$out/ais-testbed.sewer"
sed -n '1,12p' "$out/ais-testbed.sewer"
echo "..."
echo; echo "\$ sewerplan generate --manholes 100000 --topology meshed --seed 2 -o $out/city.json --mission-tasks 20 --mission-out $out/city-mission.json"
$sp generate --manholes 100000 --topology meshed --seed 2 -o "$out/city.json" --mission-tasks 20 \
  --mission-out "$out/city-mission.json"
$sp info --map "$out/city.json"
# The 20 tasks lie all over the robot's range (--mission-spread uniform, the default): more than one
# battery can do, so the planner selects the most it can do and still end the mission.
echo; echo "\$ sewerplan plan --select-goals --map $out/city.json --mission $out/city-mission.json -o $out/city.plan"
$sp plan --select-goals --map "$out/city.json" --mission "$out/city-mission.json" -o "$out/city.plan"
$sp check --select-goals --map "$out/city.json" --mission "$out/city-mission.json" "$out/city.plan"
echo; echo "\$ sewerplan simulate --map datasets/ais-testbed/map.json --mission datasets/ais-testbed/missions/paper.json --faults datasets/ais-testbed/faults/demo.json --log $out/events.jsonl"
$sp simulate --map datasets/ais-testbed/map.json --mission datasets/ais-testbed/missions/paper.json \
  --faults datasets/ais-testbed/faults/demo.json --log "$out/events.jsonl"
echo "(event log: $out/events.jsonl)"

ais=datasets/ais-testbed/map.json
mission=datasets/ais-testbed/missions/paper.json
echo; echo "\$ sewerplan render --map $ais --mission $mission --log $out/events.jsonl --faults datasets/ais-testbed/faults/demo.json -o $out/demo.svg"
$sp render --map "$ais" --mission "$mission" --log "$out/events.jsonl" \
  --faults datasets/ais-testbed/faults/demo.json -o "$out/demo.svg"

echo; echo "\$ sewerplan sim-node --pty --map $ais --mission $mission --faults datasets/ais-testbed/faults/demo.json &"
$sp sim-node --pty --map "$ais" --mission "$mission" --faults datasets/ais-testbed/faults/demo.json \
  > "$out/node.out" 2> "$out/node.err" &
node_pid=$!
trap 'kill "$node_pid" 2>/dev/null || true' EXIT
pty=""
for _ in $(seq 1 100); do
  pty=$(head -1 "$out/node.out" 2>/dev/null || true)
  [ -n "$pty" ] && break
  sleep 0.1
done
echo "simulated node on $pty"
echo "\$ sewerplan simulate --map $ais --mission $mission --can slcan:$pty --can-log $out/can.log -q"
$sp simulate --map "$ais" --mission "$mission" --can "slcan:$pty" --can-log "$out/can.log" -q
kill "$node_pid" 2>/dev/null || true
wait "$node_pid" 2>/dev/null || true
echo "(bus traffic in candump format: $out/can.log, $(wc -l < "$out/can.log") frames)"

echo; echo "\$ sewerplan motion precompute --map $out/ais/map.json"
mkdir -p "$out/ais"
cp "$ais" "$out/ais/map.json"
$sp motion precompute --map "$out/ais/map.json"
echo; echo "\$ sewerplan plan --map $out/ais/map.json --mission $mission"
$sp plan --map "$out/ais/map.json" --mission "$mission" -o "$out/paper-motion.plan"

echo; echo "\$ sewerplan campaign --map $ais --mission $mission --runs 500 --seed 1 --jobs $(nproc) -o $out/campaign"
$sp campaign --map "$ais" --mission "$mission" --runs 500 --seed 1 --jobs "$(nproc)" -o "$out/campaign"
echo "(pictures: $out/demo.svg, $out/campaign/summary.svg)"
