#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Issue 30: Ctrl-C (SIGINT) halts `simulate` at once, also while the map loads and while a plan is
# being computed (the halt is the planner's cancel), and the report and the log are still written.
# Usage: halt_test.sh PATH_TO_SEWERPLAN
set -uo pipefail
sp=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
passed=0

# A network whose first plan takes seconds (12.75 s on 5,000 manholes with 300 tasks before the
# fix), and a bigger one whose map takes a while to load.
"$sp" generate --manholes 5000 --seed 3 --topology meshed -o "$tmp/m.json" --mission-tasks 300 \
  --mission-out "$tmp/mission.json" > /dev/null || { echo "FAIL: generate"; exit 1; }

# check NAME: the simulate of $sim_pid ended halted with exit 4, its report out, its log whole and
# without a plan (the plan was cancelled, or not begun).
check() {
  local name=$1
  wait "$sim_pid"
  local got=$?
  if [ "$got" -eq 4 ] && grep -q '^halted' "$tmp/$name.out" && grep -q 'tasks dropped: 300' "$tmp/$name.out" &&
    [ "$(wc -l < "$tmp/$name.jsonl")" -eq 1 ] && grep -q '"outcome":"halted"' "$tmp/$name.jsonl"; then
    passed=$((passed + 1))
  else
    echo "FAIL: SIGINT $name -> exit $got (want 4); report and log:"
    tail -8 "$tmp/$name.out"; tail -3 "$tmp/$name.err"; tail -3 "$tmp/$name.jsonl"
    failures=$((failures + 1))
  fi
}

# While a plan is computed: the log is opened after the map and mission are read, right before the
# first plan; SIGINT then lands in the planner.
"$sp" simulate --map "$tmp/m.json" --mission "$tmp/mission.json" -q --log "$tmp/plan.jsonl" \
  > "$tmp/plan.out" 2> "$tmp/plan.err" &
sim_pid=$!
for _ in $(seq 1 3000); do
  [ -e "$tmp/plan.jsonl" ] && break
  sleep 0.01
done
sleep 0.2
start=$(date +%s.%N)
kill -INT "$sim_pid"
check plan
echo "halt during the plan: exited $(echo "$(date +%s.%N) - $start" | bc) s after SIGINT"

# While the map loads: SIGINT right away.
"$sp" simulate --map "$tmp/m.json" --mission "$tmp/mission.json" -q --log "$tmp/load.jsonl" \
  > "$tmp/load.out" 2> "$tmp/load.err" &
sim_pid=$!
# A background job of a script starts with SIGINT ignored, so the signal is sent once the command
# has put its handler in place (the first thing `simulate` does, before it reads the map): the
# handler's bit in /proc/PID/status SigCgt (SIGINT is signal 2: mask 0x2). A sanitizer build starts
# slowly, so no fixed sleep would do.
for _ in $(seq 1 5000); do
  caught=$(awk '/^SigCgt:/ {print $2}' "/proc/$sim_pid/status" 2> /dev/null)
  [ -n "$caught" ] && [ $((0x$caught & 2)) -ne 0 ] && break
  sleep 0.001
done
kill -INT "$sim_pid"
check load

echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
