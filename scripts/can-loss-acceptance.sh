#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The CAN job protocol under lost frames, end to end (issue 30, docs/can.md): a mission runs over
# SLCAN through a pseudo-terminal against `sewerplan sim-node` with frames lost at random (1, 5
# and 20 %, seeds 1..SEEDS) and with every copy of one job's result lost until the reboot that
# follows (lose-result=J for every STEP-th job), and its outcome (how it ended, where, the tasks
# done and dropped) must equal the loss-free run's. Run on the AIS mission and on a generated
# 1,000-manhole mission. Prints a Markdown table (the one in docs/can.md) and exits 1 when an
# outcome differs. Slow (wall-time timeouts, 0.5 s and 2 s per lost answer): not run in CI; the
# AIS cases, and every single-frame loss of a turn, a drive, a sample and a reboot, are unit tests
# (tests/executor/can_mission_test.cc).
#
# Usage: scripts/can-loss-acceptance.sh PATH_TO_SEWERPLAN [MANHOLES=1000] [TASKS=20] [SEEDS=2]
#        [STEP=50]
set -uo pipefail
sp=${1:?usage: $0 PATH_TO_SEWERPLAN [MANHOLES] [TASKS] [SEEDS] [STEP]}
manholes=${2:-1000}
tasks=${3:-20}
seeds=${4:-2}
step=${5:-50}
src=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
node_pid=""
cleanup() {
  if [ -n "$node_pid" ]; then kill "$node_pid" 2>/dev/null; wait "$node_pid" 2>/dev/null; fi
  rm -rf "$tmp"
}
trap cleanup EXIT
differ=0

# The outcome of a `simulate --json` report: outcome, end, tasks done, tasks dropped.
outcome() {
  python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); print(json.dumps([j["outcome"], j["end"], j["tasks_done"], j["dropped"]]))' "$1"
}

# run MAP MISSION BUS_FAULTS NAME: the mission over SLCAN against a node with those faults.
run_over_can() {
  local map=$1 mission=$2 faults=$3 name=$4
  "$sp" sim-node --pty --map "$map" --mission "$mission" --bus-faults "$faults" \
    > "$tmp/node.out" 2> "$tmp/node.err" &
  node_pid=$!
  local pty=""
  for _ in $(seq 1 200); do
    pty=$(head -1 "$tmp/node.out" 2>/dev/null)
    [ -n "$pty" ] && break
    sleep 0.05
  done
  "$sp" simulate --map "$map" --mission "$mission" --can "slcan:$pty" --json -q \
    > "$tmp/$name.json" 2> "$tmp/$name.err"
  kill -INT "$node_pid" 2>/dev/null
  wait "$node_pid" 2>/dev/null
  node_pid=""
}

# check MISSION_NAME MAP MISSION BASELINE_JSON FAULTS
check() {
  local label=$1 map=$2 mission=$3 base=$4 faults=$5
  run_over_can "$map" "$mission" "$faults" run
  local link verdict
  link=$(grep -o '[0-9]* retries, [0-9]* timeouts' "$tmp/run.err" | head -1)
  if [ -s "$tmp/run.json" ] && [ "$(outcome "$tmp/run.json")" = "$(outcome "$base")" ]; then
    verdict="same"
  else
    verdict="DIFFERS: $(head -c 300 "$tmp/run.json" 2>/dev/null) $(tail -2 "$tmp/run.err")"
    differ=1
  fi
  local ended
  ended=$(python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); print(j["outcome"], len(j["tasks_done"]), "tasks")' "$tmp/run.json" 2>/dev/null)
  echo "| $label | \`$faults\` | $ended | $verdict | $link |"
}

acceptance() {
  local label=$1 map=$2 mission=$3
  "$sp" simulate --map "$map" --mission "$mission" --json -q > "$tmp/base-$label.json" 2>/dev/null
  local jobs
  jobs=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["jobs"])' "$tmp/base-$label.json")
  for rate in 0.01 0.05 0.2; do
    for seed in $(seq 1 "$seeds"); do
      check "$label" "$map" "$mission" "$tmp/base-$label.json" "drop-rate=$rate;seed=$seed"
    done
  done
  for job in $(seq 0 "$step" $((jobs - 1))); do
    check "$label" "$map" "$mission" "$tmp/base-$label.json" "lose-result=$job"
  done
}

echo "| mission | bus faults | outcome | vs loss-free | link |"
echo "|---|---|---|---|---|"
acceptance "AIS paper" "$src/datasets/ais-testbed/map.json" \
  "$src/datasets/ais-testbed/missions/paper.json"
"$sp" generate --manholes "$manholes" --seed 1 -o "$tmp/gen.json" --mission-tasks "$tasks" \
  --mission-out "$tmp/gen-mission.json" > /dev/null
acceptance "generated $manholes" "$tmp/gen.json" "$tmp/gen-mission.json"
exit "$differ"
