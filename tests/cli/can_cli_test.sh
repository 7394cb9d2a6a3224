#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The CAN commands end to end (docs/can.md): `sim-node --pty` serves the simulated robot over
# SLCAN, `simulate --can slcan:PTY` runs the paper's mission through it with the report and event
# log of the in-process run, `--can-log` records a candump log and `--replay` plays it back; and
# the errors name the bus or the file. Usage: can_cli_test.sh PATH_TO_SEWERPLAN SOURCE_DIR
set -uo pipefail
sp=$1
src=$2
tmp=$(mktemp -d)
node_pid=""
cleanup() {
  if [ -n "$node_pid" ]; then kill "$node_pid" 2>/dev/null; wait "$node_pid" 2>/dev/null; fi
  rm -rf "$tmp"
}
trap cleanup EXIT
source "$(dirname "${BASH_SOURCE[0]}")/expect.sh"

same() {  # same WHAT FILE_A FILE_B
  if cmp -s "$2" "$3"; then
    passed=$((passed + 1))
  else
    echo "FAIL: $1 differ:"
    diff "$2" "$3" | head -10
    failures=$((failures + 1))
  fi
}

# Starts a node with extra options; sets node_pid and pty. Its output goes to $node_files.out and
# .err.
node_files=$tmp/node
start_node() {
  "$sp" sim-node --pty --map "$ais" --mission "$mission" "$@" > "$node_files.out" \
    2> "$node_files.err" &
  node_pid=$!
  pty=""
  for _ in $(seq 1 100); do
    pty=$(head -1 "$node_files.out" 2>/dev/null)
    [ -n "$pty" ] && break
    sleep 0.05
  done
  if [ -z "$pty" ]; then
    echo "FAIL: sim-node printed no pty"; cat "$node_files.err"; failures=$((failures + 1))
  fi
}

stop_node() {
  kill "$node_pid" 2>/dev/null
  wait "$node_pid" 2>/dev/null
  node_pid=""
}

# Planning times are wall-clock: not compared.
strip_planning() { sed -E 's/"planning_ms":[0-9.e+-]+//g; s/\(planning [^)]*\)//' "$1"; }

ais=$src/datasets/ais-testbed/map.json
mission=$src/datasets/ais-testbed/missions/paper.json
demo=$src/datasets/ais-testbed/faults/demo.json

# In process, then over the bus, then from the bus's candump log.
"$sp" simulate --map "$ais" --mission "$mission" --faults "$demo" --log "$tmp/local.jsonl" -q > "$tmp/local.out"
start_node --faults "$demo"
# (One mission per node: the node's robot stays where the mission left it.)
"$sp" simulate --map "$ais" --mission "$mission" --can "slcan:$pty" --can-log "$tmp/run.log" \
  --log "$tmp/can.jsonl" -q > "$tmp/can.out" 2> "$tmp/can.err"
stop_node
expect 0 'mission ended at pipe P9' -- cat "$tmp/can.out"
expect 0 "CAN link slcan:$pty: 0 retries, 0 timeouts" -- cat "$tmp/can.err"
expect 0 'sim-node: 33 requests, 32 jobs run' -- cat "$tmp/node.err"
"$sp" simulate --map "$ais" --mission "$mission" --replay "$tmp/run.log" --log "$tmp/replay.jsonl" -q > "$tmp/replay.out" 2> /dev/null
strip_planning "$tmp/local.jsonl" > "$tmp/a"; strip_planning "$tmp/can.jsonl" > "$tmp/b"
same "event logs in process and over SLCAN" "$tmp/a" "$tmp/b"
strip_planning "$tmp/replay.jsonl" > "$tmp/c"
same "event logs over SLCAN and replayed" "$tmp/b" "$tmp/c"
strip_planning "$tmp/local.out" > "$tmp/a"; strip_planning "$tmp/can.out" > "$tmp/b"
strip_planning "$tmp/replay.out" > "$tmp/c"
same "reports in process and over SLCAN" "$tmp/a" "$tmp/b"
same "reports in process and replayed" "$tmp/a" "$tmp/c"
expect 0 '^\([0-9]{10}\.[0-9]{6}\) can0 [0-9A-F]{8}#[0-9A-F]*$' -- head -1 "$tmp/run.log"
# A candump log that cannot be written: the replayed mission still ends, the log is named, exit 3.
expect 3 'cannot write /dev/full: No space left on device \([0-9]+ of [0-9]+ writes lost\)' -- \
  "$sp" simulate --map "$ais" --mission "$mission" --replay "$tmp/run.log" --can-log /dev/full -q
expect 3 'mission ended at pipe P9' -- \
  "$sp" simulate --map "$ais" --mission "$mission" --replay "$tmp/run.log" --can-log /dev/full -q

# Issue 29: a world that is not the map. sim-node builds the true world and sensing that simulate
# builds in process from the same --world-errors and --world-seed; the job results carry the
# odometry and each manhole's observed signature, so the run over the bus is the run in process,
# arrival for arrival; and each turn's angle as the robot's joints measured it, so the measured
# map is the same too, turns and all.
SOURCE_DATE_EPOCH=1796545800 "$sp" simulate --map "$ais" --mission "$mission" \
  --world-errors realistic --world-seed 3 --log "$tmp/world-local.jsonl" \
  --corrected-map "$tmp/world-map.json" -q > "$tmp/world-local.out"
cp "$tmp/world-map.measurements.json" "$tmp/world-local.measurements.json"
start_node --world-errors realistic --world-seed 3
SOURCE_DATE_EPOCH=1796545800 "$sp" simulate --map "$ais" --mission "$mission" \
  --can "slcan:$pty" --log "$tmp/world-can.jsonl" --corrected-map "$tmp/world-map.json" -q \
  > "$tmp/world-can.out" 2> /dev/null
stop_node
expect 0 '"turns": \[' -- cat "$tmp/world-map.measurements.json"
same "measurements in a realistic world in process and over SLCAN" \
  "$tmp/world-local.measurements.json" "$tmp/world-map.measurements.json"
expect 0 '"type":"arrival".*"observed":' -- cat "$tmp/world-can.jsonl"
strip_planning "$tmp/world-local.jsonl" > "$tmp/a"; strip_planning "$tmp/world-can.jsonl" > "$tmp/b"
same "event logs in a realistic world in process and over SLCAN" "$tmp/a" "$tmp/b"
strip_planning "$tmp/world-local.out" > "$tmp/a"; strip_planning "$tmp/world-can.out" > "$tmp/b"
same "reports in a realistic world in process and over SLCAN" "$tmp/a" "$tmp/b"
# The world is the node's: simulate refuses it with --can (it would not reach the robot) and
# --replay; sim-node names a bad profile.
expect 2 'are the node.s with --can: give them to sim-node' -- \
  "$sp" simulate --map "$ais" --mission "$mission" --can slcan:/dev/null --world-seed 3
expect 2 'are not for --replay' -- \
  "$sp" simulate --map "$ais" --mission "$mission" --replay "$tmp/run.log" --world-errors realistic
expect 2 "sim-node: --world-errors: unknown profile 'realism'" -- \
  "$sp" sim-node --pty --map "$ais" --mission "$mission" --world-errors realism

# mission_over_bus NAME BUS_FAULTS [OPTION...]: the paper's mission over the bus to a node with
# BUS_FAULTS, in a subshell of its own (node and all): its output goes to $tmp/NAME.out, its exit
# code to $tmp/NAME.code. over_bus_ran NAME then hands them to expect_ran.
mission_over_bus() {
  local name=$1 bus_faults=$2
  shift 2
  node_files=$tmp/$name-node
  start_node --bus-faults "$bus_faults"
  if [ -n "$pty" ]; then
    "$sp" simulate --map "$ais" --mission "$mission" --can "slcan:$pty" "$@" > "$tmp/$name.out" 2>&1
    echo $? > "$tmp/$name.code"
  fi
  stop_node
}
over_bus_ran() {
  ran_command="simulate over the bus ($1)"
  if [ -f "$tmp/$1.code" ]; then
    ran_code=$(cat "$tmp/$1.code")
    ran_out=$(cat "$tmp/$1.out")
  else
    ran_code=255
    ran_out="sim-node printed no pty: $(cat "$tmp/$1-node.err")"
  fi
}
# The next two missions spend their time waiting out the link's timeouts (0.5 s for an answer, 2 s
# of silence during a job), idle: they run at once, each with its own node, and are checked after.
# A node that falls silent for three requests: a malfunction, a reboot over the bus, and on.
(mission_over_bus silence 'silence=5+3') &
silence_pid=$!
# Every copy of a turn's result lost until the reboot (issue 30): the turn was sent again from the
# slot the robot had left, refused, and the robot ended stuck with the beacon on. Now the reboot
# asks the node for the lost result and the mission ends as without the loss.
(mission_over_bus lost 'lose-result=1' -q) &
lost_pid=$!
wait "$silence_pid" "$lost_pid"
over_bus_ran silence
expect_ran 0 'reason=CAN link: no acknowledgement of job'
over_bus_ran lost
expect_ran 0 'mission ended at pipe P9'

# Ctrl-C halts a running mission (Executor::halt; docs/cli.md): the node holds job 2's
# acknowledgement back for 30 s (busy, with heartbeats), so the controller is waiting on a job when
# SIGINT arrives. The mission ends "halted", the log is complete, the exit code is 4.
start_node --bus-faults 'late-ack=2@30'
"$sp" simulate --map "$ais" --mission "$mission" --can "slcan:$pty" --log "$tmp/halt.jsonl" \
  > "$tmp/halt.out" 2> "$tmp/halt.err" &
sim_pid=$!
# The log is flushed per event: the second job's line is there while the third job waits. (Up to
# 60 s: the simulator and the node start slowly on a loaded machine; the node holds for 30 s.)
for _ in $(seq 1 1200); do
  jobs_logged=$(grep -c '"type":"job"' "$tmp/halt.jsonl" 2> /dev/null || true)
  [ "${jobs_logged:-0}" -ge 2 ] && break
  sleep 0.05
done
kill -INT "$sim_pid"
wait "$sim_pid"
got=$?
stop_node
if [ "$got" -eq 4 ] && tail -1 "$tmp/halt.jsonl" | grep -q '"outcome":"halted"' &&
  grep -q 'halted' "$tmp/halt.out" && ! grep -q 'CAN link' "$tmp/halt.jsonl"; then
  passed=$((passed + 1))
else
  echo "FAIL: SIGINT during simulate --can -> exit $got (want 4), log ends:"
  tail -2 "$tmp/halt.jsonl"; tail -5 "$tmp/halt.out"; tail -5 "$tmp/halt.err"
  failures=$((failures + 1))
fi

# Errors name what is wrong.
expect 2 "--can: expected slcan:TTY or socketcan:INTERFACE, got 'can0'" -- \
  "$sp" simulate --map "$ais" --mission "$mission" --can can0
expect 3 'slcan:/dev/no-such-tty: cannot open' -- \
  "$sp" simulate --map "$ais" --mission "$mission" --can slcan:/dev/no-such-tty
expect 3 'socketcan:nosuchcan0: (this kernel has no CAN support|no such network interface)' -- \
  "$sp" simulate --map "$ais" --mission "$mission" --can socketcan:nosuchcan0
expect 3 'cannot read [^ ]*missing.log: No such file or directory' -- \
  "$sp" simulate --map "$ais" --mission "$mission" --replay "$tmp/missing.log"
printf '(1.000000) can0 123#00\n(2.000000) can0 123#0\n' > "$tmp/bad.log"
expect 1 'bad.log:2: expected 0 to 8 data bytes' -- \
  "$sp" simulate --map "$ais" --mission "$mission" --replay "$tmp/bad.log"
expect 2 'excludes' -- "$sp" simulate --map "$ais" --mission "$mission" --faults "$demo" --can slcan:/dev/null
expect 2 "--bus-faults: 'fire=1': unknown fault" -- \
  "$sp" sim-node --pty --map "$ais" --mission "$mission" --bus-faults fire=1
expect 2 'pty' -- "$sp" sim-node --map "$ais" --mission "$mission"

echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
