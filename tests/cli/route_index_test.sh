#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# sewerplan index build (issue 35; docs/cli.md, docs/formats/route-index.md): the routing index
# built beside a copy of the AIS test bed; plan and simulate use it and say so, with the same plan
# and run as without it; --route-index names another, --no-route-index ignores it; a stale index
# (another robot) and a broken file are errors (exit 1) that say what is wrong and how to remake it.
# Usage: route_index_test.sh PATH_TO_SEWERPLAN SOURCE_DIR
set -uo pipefail
sp=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
source "$(dirname "${BASH_SOURCE[0]}")/expect.sh"
expect_timeout=60  # a hang fails

cp "$src/datasets/ais-testbed/map.json" "$tmp/map.json"
mission=$src/datasets/ais-testbed/missions/paper.json
faults=$src/datasets/ais-testbed/faults/blocked-p5.json

# Without an index beside the map: nothing said, the plan as ever.
"$sp" plan --map "$tmp/map.json" --mission "$mission" -o "$tmp/without.txt" 2>"$tmp/without.err"
check "plan without an index succeeds" test $? -eq 0
check "plan without an index says nothing of one" bash -c "! grep -q 'routing index' '$tmp/without.err'"

run_once "$sp" index build --map "$tmp/map.json"
expect_ran 0 "^index: [0-9]+ positions, [0-9]+ moves, [0-9]+ shortcuts; "
expect_ran 0 "wrote $tmp/map.route-index.bin \\([0-9]+ bytes\\)"
check "the index is beside the map" test -s "$tmp/map.route-index.bin"
"$sp" index build --map "$tmp/map.json" -o "$tmp/again.bin" >/dev/null
check "the build is deterministic" cmp -s "$tmp/map.route-index.bin" "$tmp/again.bin"

# plan and simulate find it and say so; the plan and the run are the same.
expect 0 "index: using the routing index $tmp/map.route-index.bin \\([0-9]+ positions\\)" -- \
  "$sp" plan --map "$tmp/map.json" --mission "$mission" -o "$tmp/with.txt"
check "the plan with the index is the plan without" cmp -s "$tmp/with.txt" "$tmp/without.txt"
"$sp" plan --map "$tmp/map.json" --mission "$mission" --json 2>/dev/null >"$tmp/with.json"
check "the compile took its routes from the index: no route search" python3 -c "
import json
s = json.load(open('$tmp/with.json'))['statistics']['compile']
assert s['route_searches'] == 0, s
"
"$sp" plan --map "$tmp/map.json" --mission "$mission" --no-route-index --json 2>"$tmp/none.err" \
  >"$tmp/none.json"
check "--no-route-index: the compile searches" python3 -c "
import json
s = json.load(open('$tmp/none.json'))['statistics']['compile']
assert s['route_searches'] > 0, s
"
check "--no-route-index says nothing of one" bash -c "! grep -q 'routing index' '$tmp/none.err'"
"$sp" simulate --map "$tmp/map.json" --mission "$mission" --faults "$faults" >"$tmp/sim-with.txt" \
  2>"$tmp/sim-with.err"
check "simulate with the index succeeds" test $? -eq 0
check "simulate says it uses the index" grep -q "index: using the routing index" "$tmp/sim-with.err"
"$sp" simulate --map "$tmp/map.json" --mission "$mission" --faults "$faults" --no-route-index \
  >"$tmp/sim-without.txt" 2>/dev/null
# The same but for the planning times it reports.
untimed() { sed -E 's/planning_ms=[0-9.]+//; s/\(planning [^)]*\)//' "$1"; }
check "the run with the index is the run without" \
  cmp -s <(untimed "$tmp/sim-with.txt") <(untimed "$tmp/sim-without.txt")
check "the run replanned" grep -q "reason=failure\|1 replans" "$tmp/sim-with.txt"

# --route-index names another file; one for another robot is stale.
"$sp" index build --map "$tmp/map.json" --profile makro-plus -o "$tmp/plus.bin" >/dev/null
run_once "$sp" plan --map "$tmp/map.json" --mission "$mission" --route-index "$tmp/plus.bin"
expect_ran 1 "the routing index $tmp/plus.bin is stale: it was built for another map, robot profile"
expect_ran 1 "remake it with 'sewerplan index build'"
expect_ran 1 "use --no-route-index to plan without it"
expect 1 "is stale" -- "$sp" simulate --map "$tmp/map.json" --mission "$mission" \
  --route-index "$tmp/plus.bin"
# The same index kept beside a map: said so, with how to remake it, and the plan (the same plan)
# made without it; simulate alike.
cp "$tmp/map.json" "$tmp/other.json"
cp "$tmp/plus.bin" "$tmp/other.route-index.bin"
expect 0 "index: the routing index $tmp/other.route-index.bin is stale.*planning without it" -- \
  "$sp" plan --map "$tmp/other.json" --mission "$mission" -o "$tmp/stale-plan.txt"
check "the plan beside a stale index is the plan" cmp -s "$tmp/stale-plan.txt" "$tmp/without.txt"
expect 0 "index: the routing index $tmp/other.route-index.bin is stale" -- \
  "$sp" simulate --map "$tmp/other.json" --mission "$mission"
# --mission takes the profile from the mission, as plan does: its index is not stale for it.
"$sp" index build --map "$tmp/map.json" --mission "$mission" -o "$tmp/from-mission.bin" >/dev/null
check "an index built from the mission's profile serves its plan" \
  "$sp" plan --map "$tmp/map.json" --mission "$mission" --route-index "$tmp/from-mission.bin" -q
expect 2 "excludes" -- "$sp" index build --map "$tmp/map.json" --mission "$mission" \
  --profile makro-plus
expect 3 "$tmp/no-such-mission.json" -- "$sp" index build --map "$tmp/map.json" \
  --mission "$tmp/no-such-mission.json"
# A broken file: truncated, not an index, missing.
head -c 100 "$tmp/map.route-index.bin" >"$tmp/cut.bin"
expect 1 "$tmp/cut.bin: truncated or corrupt: its counts" -- \
  "$sp" plan --map "$tmp/map.json" --mission "$mission" --route-index "$tmp/cut.bin"
expect 1 "$tmp/map.json: not a sewerplan routing index" -- \
  "$sp" plan --map "$tmp/map.json" --mission "$mission" --route-index "$tmp/map.json"
expect 3 "cannot read $tmp/missing.bin" -- \
  "$sp" plan --map "$tmp/map.json" --mission "$mission" --route-index "$tmp/missing.bin"
# The index is of the moves with the motion table beside the map (where this build can plan
# one): an index built before the table is stale with it, fine again with --no-motion, and one
# built with the table is used with it.
if "$sp" motion precompute --map "$tmp/map.json" -q >/dev/null 2>&1; then
  # Beside the map, a stale index is said so, and the plan made without it (the same plan).
  expect 0 "index: the routing index $tmp/map.route-index.bin is stale" -- \
    "$sp" plan --map "$tmp/map.json" --mission "$mission" -q
  expect 0 "remake it with 'sewerplan index build'" -- \
    "$sp" plan --map "$tmp/map.json" --mission "$mission" -q
  expect 1 "is stale" -- "$sp" plan --map "$tmp/map.json" --mission "$mission" -q \
    --route-index "$tmp/map.route-index.bin"
  expect 0 "" -- "$sp" plan --map "$tmp/map.json" --mission "$mission" -q --no-motion
  "$sp" index build --map "$tmp/map.json" -q >/dev/null
  expect 0 "index: using the routing index" -- "$sp" plan --map "$tmp/map.json" --mission "$mission" \
    -q -o "$tmp/motion-plan.txt"
  rm -f "$tmp/map.motion.json"
fi

# A time limit stops the build without an index (exit 5).
expect 5 "the routing index's build reached its time limit" -- \
  "$sp" index build --map "$tmp/map.json" --time-limit 1e-9 -o "$tmp/limited.bin"
check "a stopped build writes no index" test ! -e "$tmp/limited.bin"

# Inspection findings (--condition) close pipes for the plan: the index's routes through them are
# searched on the plan's own graph (guided by the index), and the plan is the plan without it.
# An index built with the same --condition is not stale for those plans; a findings file that
# names pipes the map has not is an error that says so.
cp "$src/datasets/swmm/swmmio-state-plane.inp" "$tmp/sp.inp"
"$sp" convert "$tmp/sp.inp" -o "$tmp/sp.json" >/dev/null 2>&1
spm=$src/datasets/condition/swmm-state-plane/mission.json
findings=$src/datasets/condition/swmm-state-plane/zustand.xml
run_once "$sp" index build --map "$tmp/sp.json" --mission "$spm" --condition "$findings"
expect_ran 0 "wrote $tmp/sp.route-index.bin"
for risk in impassable expected; do
  expect 0 "index: using the routing index $tmp/sp.route-index.bin" -- \
    "$sp" plan --map "$tmp/sp.json" --mission "$spm" --condition "$findings" --risk "$risk" \
    --select-goals -o "$tmp/sp-with-$risk.txt"
  "$sp" plan --map "$tmp/sp.json" --mission "$spm" --condition "$findings" --risk "$risk" \
    --select-goals --no-route-index -o "$tmp/sp-without-$risk.txt" 2>/dev/null
  check "with findings (--risk $risk), the plan with the index is the plan without" \
    cmp -s "$tmp/sp-with-$risk.txt" "$tmp/sp-without-$risk.txt"
done
"$sp" plan --map "$tmp/sp.json" --mission "$spm" --condition "$findings" --select-goals --json \
  2>/dev/null >"$tmp/sp-with.json"
check "routes the findings touch were searched toward their targets" python3 -c "
import json
s = json.load(open('$tmp/sp-with.json'))['statistics']['compile']
assert s['guided_searches'] > 0 and s['index_rows'] > 0, s
"
expect 3 "cannot read $tmp/no-such-findings.xml" -- "$sp" index build --map "$tmp/sp.json" \
  --mission "$spm" --condition "$tmp/no-such-findings.xml"

# Usage errors and a missing map.
expect 2 "time-limit" -- "$sp" index build --map "$tmp/map.json" --time-limit -1
expect 2 "map" -- "$sp" index build
expect 3 "cannot read $tmp/no-such-map.json" -- "$sp" index build --map "$tmp/no-such-map.json"

echo "route_index_test: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
