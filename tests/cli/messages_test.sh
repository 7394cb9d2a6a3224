#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Messages a person can act on (issue 31), through the command line: values told apart from the
# limit they break, control characters of the input escaped, a JSON number beyond a double named by
# line, SWMM networks read with warnings instead of refused, and `info` listing apart what the
# findings close in pipes the robot cannot enter anyway.
# Usage: messages_test.sh PATH_TO_SEWERPLAN SOURCE_DIR
set -uo pipefail
sp=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
source "$(dirname "${BASH_SOURCE[0]}")/expect.sh"

# refute 'REGEX' -- COMMAND...: the output of COMMAND does not match.
refute() {
  local pattern=$1
  shift 2
  "$@" > "$tmp/refute.txt" 2>&1
  if grep -qE -- "$pattern" "$tmp/refute.txt"; then
    echo "FAIL: $* printed /$pattern/"
    failures=$((failures + 1))
  else
    passed=$((passed + 1))
  fi
}

# M1 -P1 (0.4 m)- M2 -P2 (0.15 m: too narrow for the MAKRO's 0.30 to 0.60 m)- M3, and P3 from M2
# whose end lies 0.3048 m (one foot) above P1's: a step just beyond the 0.30 m limit. A collapse
# (BAC C) in P1, which the robot could drive, and one in P2, which it cannot enter anyway.
cat > "$tmp/map.json" <<'JSON'
{"format": "sewerplan-map", "version": 1, "name": "closures",
 "manholes": [
  {"name": "M1", "x_m": 0, "y_m": 0, "diameter_m": 1.0, "exit": true,
   "slots": [{"pipe": "P1", "azimuth_deg": 0, "invert_m": 0}]},
  {"name": "M2", "x_m": 10, "y_m": 0, "diameter_m": 1.0,
   "slots": [{"pipe": "P1", "azimuth_deg": 180, "invert_m": 0},
             {"pipe": "P2", "azimuth_deg": 0, "invert_m": 0},
             {"pipe": "P3", "azimuth_deg": 90, "invert_m": 0.3048}]},
  {"name": "M3", "x_m": 20, "y_m": 0, "diameter_m": 1.0, "exit": true,
   "slots": [{"pipe": "P2", "azimuth_deg": 180, "invert_m": 0}]},
  {"name": "M4", "x_m": 10, "y_m": 10, "diameter_m": 1.0, "exit": true,
   "slots": [{"pipe": "P3", "azimuth_deg": -90, "invert_m": 0}]}],
 "pipes": [
  {"name": "P1", "from": "M1", "to": "M2", "length_m": 10, "diameter_m": 0.4},
  {"name": "P2", "from": "M2", "to": "M3", "length_m": 10, "diameter_m": 0.15},
  {"name": "P3", "from": "M2", "to": "M4", "length_m": 10, "diameter_m": 0.4}],
 "findings": [
  {"pipe": "P1", "code": "BAC", "characterisation": "C", "offset_m": 5},
  {"pipe": "P2", "code": "BAC", "characterisation": "C", "offset_m": 2}]}
JSON

# The step of 0.3048 m was shown as "step 0.30 m > 0.30".
expect 0 'step 0\.305 m > 0\.300$' -- "$sp" info --map "$tmp/map.json" --profile makro-1.1
# What the findings close: P1 as before; P2 apart, since the robot cannot enter it anyway.
"$sp" info --map "$tmp/map.json" --profile makro-1.1 > "$tmp/info.txt" 2>&1
expect 0 'ok' -- python3 -c "
lines = open('$tmp/info.txt').read().splitlines()
i = lines.index('closed by findings 1')
assert lines[i + 1] == '  pipe P1 at 5.00 m: BAC collapse', lines[i:]
assert lines[i + 2] == ('closed by findings in pipes the robot cannot enter anyway 1 '
                        '(no change for a plan)'), lines[i:]
assert lines[i + 3] == '  pipe P2 at 2.00 m: BAC collapse (the pipe is too narrow)', lines[i:]
print('ok')"
"$sp" info --map "$tmp/map.json" --profile makro-1.1 --json > "$tmp/info.json"
expect 0 'ok' -- python3 -c "
import json, sys
d = json.load(open('$tmp/info.json'))['driveability']
assert [c['pipe'] for c in d['closed_by_findings']] == ['P1'], d
apart = d['closed_by_findings_in_undrivable_pipes']
assert [(c['pipe'], c['pipe_not_driveable']) for c in apart] == [('P2', 'too narrow')], apart
print('ok')"

# A number beyond a double: file, line and column, in our words.
printf '{"format": "sewerplan-map",\n "version": 1e999}\n' > "$tmp/huge.json"
expect 1 'huge\.json:2:13: error: number 1e999 is out of range' -- \
  "$sp" validate --map "$tmp/huge.json"
refute 'json\.exception|number overflow' -- "$sp" validate --map "$tmp/huge.json"

# A limit broken by less than the printed digits: "at most 1e+07 m, got 1e+07".
sed 's/"x_m": 20, "y_m": 0/"x_m": 10000000.5, "y_m": 0/' "$tmp/map.json" > "$tmp/far.json"
expect 1 'x must be at most 10000000 m, got 10000000\.5' -- "$sp" validate --map "$tmp/far.json"

# A NUL in a name (and the NULs of UTF-16 text): escaped, never sent to the terminal raw.
printf '[JUNCTIONS]\nJ1 10\nJ\0002 9\n[CONDUITS]\nC1 J1 J\0002 10 0.01 0 0\n[XSECTIONS]\nC1 CIRCULAR 0.5\n' \
  > "$tmp/nul.inp"
expect 1 "manhole name 'J\\\\x002'" -- "$sp" validate --map "$tmp/nul.inp"
"$sp" validate --map "$tmp/nul.inp" > "$tmp/nul.txt" 2>&1
if od -An -tx1 "$tmp/nul.txt" | grep -qE '(^| )00( |$)'; then
  echo "FAIL: a NUL reached the terminal"; failures=$((failures + 1))
else
  passed=$((passed + 1))
fi

# SWMM: a schematic drawing beyond 1e7 and a pond wider than any manhole are read with warnings.
cat > "$tmp/pond.inp" <<'INP'
[OPTIONS]
FLOW_UNITS CMS
[JUNCTIONS]
J1 10 2
J2 9.5 2
[STORAGE]
POND 9 3 0 FUNCTIONAL 20000 0 0
[CONDUITS]
C1 J1 J2 20 0.013 0 0
C2 J2 POND 30 0.013 0 0
C3 J2 J2 5 0.013 0 0
[XSECTIONS]
C1 CIRCULAR 0.5
C2 CIRCULAR 0.5
C3 CIRCULAR 0.5
[MAP]
Units None
[COORDINATES]
J1 25000000 0
J2 25000020 0
POND 25000050 0
INP
# The conduit from J2 to itself: one error at its row, no contradicting follow-on.
expect 1 'pond\.inp:11: error: pipe C3: joins manhole J2 to itself' -- "$sp" validate --map "$tmp/pond.inp"
refute 'second time|no slot for it' -- "$sp" validate --map "$tmp/pond.inp"
sed -i '/^C3 /d' "$tmp/pond.inp"
expect 0 'storage unit POND is 160 m across' -- "$sp" validate --map "$tmp/pond.inp"
expect 0 'UNITS NONE: the coordinates are a schematic drawing' -- "$sp" validate --map "$tmp/pond.inp"
expect 0 'valid \(2 manholes, 2 pipes' -- "$sp" validate --map "$tmp/pond.inp"

# Issue 30: a "no plan" on a real SWMM network names the limit and its object, not the battery,
# also with a 100 kWh battery, with and without --select-goals. On the swmmio state-plane model,
# lowered into J1-032, the robot cannot get to pipe J1-035.1: at J4-001 the turn into it is
# 159.14 degrees (and 94.81 into J4-001.1); the other way, J1-194.1, is too narrow.
cat > "$tmp/turn.json" <<'JSON'
{"format": "sewerplan-mission", "version": 1,
 "profile": {"base": "makro-plus", "battery_wh": 100000},
 "start": {"manhole": "J1-032"},
 "tasks": [{"name": "scan", "type": "inspect_pipe", "pipe": "J1-035.1"}], "exits": "all"}
JSON
state_plane=$2/datasets/swmm/swmmio-state-plane.inp
expect 4 "in the way: manhole J4-001 from slot 1 \(pipe J1-032\.1\) to slot 2 \(pipe J1-035\.1\) turns 159\.14 deg, beyond makro-plus[-a-z]*.s 90\.00 deg turn limit" -- \
  "$sp" plan -q --map "$state_plane" --mission "$tmp/turn.json"
expect 4 "; pipe J1-194\.1 is 0\.20 m, narrower than makro-plus[-a-z]*.s 0\.30 m" -- \
  "$sp" plan -q --map "$state_plane" --mission "$tmp/turn.json"
refute 'battery|Wh' -- "$sp" plan -q --map "$state_plane" --mission "$tmp/turn.json"
expect 0 '"reason": "no route from the start \(in manhole J1-032\) reaches pipe J1-035\.1 .*in the way: ' -- \
  "$sp" plan -q --json --select-goals --map "$state_plane" --mission "$tmp/turn.json"
# A step: on the fuzz corpus' small network, C2 lies beyond a 0.90 m step at B.
cat > "$tmp/step.json" <<'JSON'
{"format": "sewerplan-mission", "version": 1, "profile": "makro-plus", "start": {"pipe": "C1"},
 "tasks": [{"type": "inspect_pipe", "pipe": "C2"}], "exits": ["A"]}
JSON
expect 4 'in the way: manhole B from slot 1 \(pipe C1\) to slot 2 \(pipe C2\) climbs a step of 0\.90 m, beyond makro-plus.s 0\.30 m step limit' -- \
  "$sp" plan -q --map "$2/fuzz/corpus/swmm/small-elevation.inp" --mission "$tmp/step.json"

echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
