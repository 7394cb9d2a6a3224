#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The command-line contract that scripts rely on: exit codes, messages that name the file and the
# object, and JSON output. Usage: cli_test.sh PATH_TO_SEWERPLAN SOURCE_DIR
set -uo pipefail
sp=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
source "$(dirname "${BASH_SOURCE[0]}")/expect.sh"

ais=$src/datasets/ais-testbed/map.json
mission=$src/datasets/ais-testbed/missions/paper.json
expect 0 "valid \(12 manholes, 14 pipes" -- "$sp" validate --map "$ais"
expect 0 "mission .*paper.json valid" -- "$sp" validate --map "$ais" --mission "$mission"
expect 0 '"valid": true' -- "$sp" validate --map "$ais" --json
run_once "$sp" validate --map "$src/tests/data/json/broken.json"
expect_ran 1 'broken.json:\$\.pipes\[1\]\.to: error: pipe P2: to names unknown manhole .C.'
expect_ran 1 'pipe P2: length must be a positive number of metres, got -2'
expect 1 '"valid": false' -- "$sp" validate --map "$src/tests/data/json/broken.json" --json
expect 3 'cannot read .*missing.json: No such file' -- "$sp" validate --map "$tmp/missing.json"
expect 2 'required' -- "$sp" validate
# The map named the old way, positionally, still works, with a deprecation note; twice is an error.
expect 0 'validate: the map as a positional argument is deprecated; use --map' -- "$sp" validate "$ais"
expect 0 'TYPE_4: 2' -- "$sp" info "$ais"
expect 0 'wrote .*\(12 manholes, 14 pipes\)' -- "$sp" convert "$ais" "$tmp/old-form.sewer"
expect 0 'wrote .*\(12 manholes, 14 pipes\)' -- "$sp" convert --map "$ais" "$tmp/old-form2.sewer"
expect 2 'give the map once' -- "$sp" validate --map "$ais" "$ais"
expect 2 'give the output once' -- "$sp" convert --map "$ais" -o "$tmp/x.sewer" "$tmp/y.sewer"
# --help and --version: the exit codes, and the version from CMake's project().
expect 0 '6  campaign: not clean' -- "$sp" --help
help_out=$ran_out
expect 0 '^sewerplan [0-9]+\.[0-9]+\.[0-9]+$' -- "$sp" --version
expect 2 '' -- "$sp" frobnicate
run_once "$sp" info --map "$ais"
expect_ran 0 'TYPE_4: 2'
expect_ran 0 'exits +4: M1, M4, M10, M12'
expect 0 '"manholes": 12' -- "$sp" info --map "$ais" --json
echo '{"format": "sewerplan-mission", "version": 1, "start": {"pipe": "P99"}, "tasks": []}' > "$tmp/m.json"
expect 1 "m.json:\\\$\\.start\\.pipe: error: unknown pipe 'P99'" -- "$sp" validate --map "$ais" --mission "$tmp/m.json"

# Conversions round-trip through every format.
expect 0 'wrote' -- "$sp" convert --map "$ais" -o "$tmp/a.sewer"
expect 0 'wrote' -- "$sp" convert --map "$tmp/a.sewer" -o "$tmp/b.json"
expect 0 'valid \(12 manholes, 14 pipes' -- "$sp" validate --map "$tmp/b.json"
if ! cmp -s <("$sp" info --map "$ais" --json | grep -v '"name"') <("$sp" info --map "$tmp/b.json" --json | grep -v '"name"'); then
  echo "FAIL: JSON -> ASCII -> JSON changed the map"; failures=$((failures + 1))
else
  passed=$((passed + 1))
fi
expect 2 'unknown format' -- "$sp" convert --map "$ais" -o "$tmp/x.out" --to xml
expect 1 'cannot tell the format' -- "$sp" convert --map "$ais" -o "$tmp/x.out"
# ... told before the map is read or made (a missing map was reported first, a large network made
# first), and nothing written.
expect 1 "$tmp/x.out: cannot tell the format" -- "$sp" convert --map "$tmp/no-such-map.json" -o "$tmp/x.out"
expect 1 'does not write them' -- "$sp" convert --map "$tmp/no-such-map.json" -o "$tmp/x.inp"
expect 1 "$tmp/g.pdf: cannot tell the format" -- "$sp" generate --manholes 5 -o "$tmp/g.pdf"
expect 0 '' -- test ! -e "$tmp/x.out" -a ! -e "$tmp/g.pdf"

# Imported sewer databases: SWMM and ISYBAU, converted to the native formats, never written.
swmm="$src/datasets/swmm/epa-example1.inp"
isybau="$src/datasets/isybau/street-2017.xml"
expect 0 'wrote .*\(14 manholes, 13 pipes\)' -- "$sp" convert --map "$swmm" -o "$tmp/ex1.json"
expect 0 'valid \(14 manholes, 13 pipes' -- "$sp" validate --map "$tmp/ex1.json"
expect 0 'wrote .*\(4 manholes, 4 pipes\)' -- "$sp" convert --map "$isybau" -o "$tmp/street.sewer"
expect 1 'does not write them' -- "$sp" convert --map "$ais" -o "$tmp/ais.inp"
expect 2 'does not write it' -- "$sp" convert --map "$ais" -o "$tmp/ais.out" --to isybau
expect 1 'net.inp:1: error: data before the first \[SECTION\]' -- \
  bash -c "printf 'x\n[JUNCTIONS]\n' > '$tmp/net.inp'; '$sp' validate '$tmp/net.inp'"
# Driveability for a robot profile.
echo '{"base": "makro-plus", "name": "low-steps", "max_step_m": 0.2}' > "$tmp/low-steps.json"
run_once "$sp" info --map "$isybau" --profile makro-plus
expect_ran 0 'too narrow +1 pipes: S4'
expect_ran 0 'S2 2<->3 \(S3, S2\): turn 116.57 deg > 90.00 step 0.35 m > 0.30'
expect 0 'reachable +3 of 4 manholes, 2 of 4 pipes .* from 1 start: S4' -- \
  "$sp" info --map "$isybau" --profile "$tmp/low-steps.json" --start S4
expect 0 '"too_wide": \[' -- "$sp" info --map "$swmm" --profile makro-plus --json
expect 1 "--start: no manhole 'M99'" -- "$sp" info --map "$isybau" --profile makro-plus --start M99
expect 2 'needs --profile' -- "$sp" info --map "$isybau" --start S1

# Issue 15: real exports. 2013 floor points, optional elements, Latin-1 names, findings.
isy=$src/datasets/isybau
expect 0 'pipe ends begin inside their manhole' -- "$sp" validate --map "$isy/street-2013.xml"
# The 2017 fixture's 116.57 deg, within half a degree (the 2013 lines end at floor points).
expect 0 'S2 2<->3 \(S3, S2\): turn (116\.[5-9][0-9]|117\.0[0-9]) deg' -- "$sp" info --map "$isy/street-2013.xml" --profile makro-plus
expect 0 'valid \(4 manholes, 4 pipes' -- "$sp" validate --map "$isy/street-optional.xml"
expect 0 'wrote .*\(4 manholes, 4 pipes\)' -- "$sp" convert --map "$isy/street-latin1.xml" -o "$tmp/latin1.json"
if grep -q '"name": "Süd3"' "$tmp/latin1.json"; then passed=$((passed + 1)); else
  echo "FAIL: the Latin-1 name Süd3 did not reach the JSON map"; failures=$((failures + 1)); fi
expect 0 '"manholes": 4' -- "$sp" info --map "$isy/street-latin1.xml" --json
expect 0 '"valid": true' -- "$sp" validate --map "$isy/street-latin1.xml" --json
printf 'sewerdb 1\nmanhole M\xfc x=0 y=0 z=0 diameter=1\n' > "$tmp/latin1.sewer"
expect 1 '"valid": false' -- "$sp" validate --map "$tmp/latin1.sewer" --json
expect 1 'not valid UTF-8' -- "$sp" validate --map "$tmp/latin1.sewer"
expect 1 'a Zustandsdaten file \(6 inspected objects\) without Stammdaten' -- \
  "$sp" validate --map "$isy/street-zustand.xml"
expect 1 'no conduit a robot could drive' -- \
  bash -c "printf '[JUNCTIONS]\nJ1 1 1\n' > '$tmp/j.inp'; '$sp' validate --strict '$tmp/j.inp'"
expect 1 'a DWA-M 150 file' -- bash -c "echo '<DATA><KG/></DATA>' > '$tmp/m150.xml'; '$sp' validate '$tmp/m150.xml'"
expect 1 'an INTERLIS transfer file' -- bash -c "echo '<TRANSFER/>' > '$tmp/t.xtf'; '$sp' validate '$tmp/t.xtf'"
expect 0 'findings +7: BAA 1, BAC 1, BAJ 1, BBA 1, BBB 1, BCD 1, BCE 1' -- \
  "$sp" info --map "$isybau" --condition "$isy/street-zustand.xml"
expect 0 'pipe S2 at 18.00 m: BAC collapse' -- \
  "$sp" info --map "$isybau" --profile makro-plus --condition "$isy/street-zustand.xml"
expect 0 '"closed_by_findings": \[' -- \
  "$sp" info --map "$isybau" --profile makro-plus --json --condition "$isy/street-zustand.xml"
expect 0 'wrote' -- "$sp" convert --map "$isybau" -o "$tmp/cond.json" --condition "$isy/street-zustand.xml"
expect 0 '"findings": 7' -- "$sp" info --map "$tmp/cond.json" --json
expect 1 'holds no inspection findings' -- "$sp" convert --map "$tmp/cond.json" -o "$tmp/cond.sewer"
# Planning with findings: the roots in pipe S1 may block; --risk avoid closes them, ignore does not.
echo '{"format": "sewerplan-mission", "version": 1, "profile": "makro-plus", "start": {"manhole": "S1"},
  "tasks": [{"name": "roots", "type": "inspect_pipe", "pipe": "S1"}]}' > "$tmp/street-mission.json"
expect 0 'INSPECT' -- "$sp" plan --map "$isybau" --mission "$tmp/street-mission.json" \
  --condition "$isy/street-zustand.xml"
expect 0 'risk: 5 places closed by inspection findings \(every risk avoided\)' -- \
  "$sp" plan --map "$isybau" --mission "$tmp/street-mission.json" --condition \
  "$isy/street-zustand.xml" --risk avoid --select-goals
# The task the findings cut off is named with its cause, not the battery (issue 30).
expect 4 "task 'roots' \(inspect_pipe\): no position the robot can reach lets it do the task: pipe S1 is blocked" -- \
  "$sp" plan --map "$isybau" --mission "$tmp/street-mission.json" \
  --condition "$isy/street-zustand.xml" --risk avoid
# --risk expected: the roots are weighed, not closed, and the route's risk is reported.
run_once "$sp" plan --map "$isybau" --mission "$tmp/street-mission.json" \
  --condition "$isy/street-zustand.xml" --risk expected
expect_ran 0 'risk: the route passes 1 possible blockages; unobstructed run 0\.70'
# Issue 34: the plan's computed stranding risk, and --max-strand-risk bounding it: 0 (the default,
# the run above) keeps the reserve to back out of S1 past the roots; 1 keeps none, but the robot
# passes the roots with the battery to back out to the start manhole, an exit: no risk either. A
# mission that ends inside S1 (a final task) can keep no reserve: the roots' 0.3 is the risk.
expect_ran 0 'stranding risk 0\.0000 \(0 hazards passed'
expect 0 '"unobstructed_probability": 0\.7' -- "$sp" plan --map "$isybau" \
  --mission "$tmp/street-mission.json" --condition "$isy/street-zustand.xml" --risk expected --json
expect 0 'stranding risk 0\.0000 \(0 hazards passed' -- "$sp" plan --map "$isybau" \
  --mission "$tmp/street-mission.json" --condition "$isy/street-zustand.xml" --risk expected \
  --max-strand-risk 1
echo '{"format": "sewerplan-mission", "version": 1, "profile": "makro-plus", "start": {"manhole": "S1"},
  "tasks": [{"name": "roots", "type": "inspect_pipe", "pipe": "S1", "final": true}]}' \
  > "$tmp/street-final.json"
expect 0 'stranding risk 0\.3000 \(1 hazard passed' -- "$sp" plan --map "$isybau" \
  --mission "$tmp/street-final.json" --condition "$isy/street-zustand.xml" --risk expected \
  --max-strand-risk 1
expect 0 '"strand_probability": 0\.3' -- "$sp" plan --map "$isybau" \
  --mission "$tmp/street-final.json" --condition "$isy/street-zustand.xml" --risk expected \
  --max-strand-risk 1 --json
for bad in 1.5 2; do
  expect 2 "--max-strand-risk: $bad is not a probability: give a number from 0 to 1" -- \
    "$sp" plan --map "$isybau" --mission "$tmp/street-mission.json" --max-strand-risk "$bad"
  expect 2 "--max-strand-risk: $bad is not a probability" -- \
    "$sp" simulate --map "$isybau" --mission "$tmp/street-mission.json" --max-strand-risk "$bad"
  expect 2 "campaign: --max-strand-risk: $bad is not a probability" -- \
    "$sp" campaign --map "$isybau" --mission "$tmp/street-mission.json" --runs 1 \
    --max-strand-risk "$bad" --out "$tmp/strand-campaign"
done
expect 2 '--max-strand-risk: must be a finite number' -- "$sp" plan --map "$isybau" \
  --mission "$tmp/street-mission.json" --max-strand-risk nan
expect 2 '--max-strand-risk: must not be negative; got -0\.1' -- "$sp" plan --map "$isybau" \
  --mission "$tmp/street-mission.json" --max-strand-risk -0.1
# A risk table from a file: the shipped default gives the same; a bad one names file and path.
expect 0 'risk: the route passes 1 possible blockages' -- "$sp" plan --map "$isybau" \
  --mission "$tmp/street-mission.json" --condition "$isy/street-zustand.xml" --risk expected \
  --risk-table "$src/datasets/condition/default-risk-table.json"
echo '{"format": "sewerplan-risk-table", "version": 1, "rules": [{"code": "BBA", "effect": "x"}]}' \
  > "$tmp/bad-table.json"
expect 1 'bad-table.json:\$\.rules\[0\]\.effect: .*unknown effect' -- "$sp" plan --map "$isybau" \
  --mission "$tmp/street-mission.json" --condition "$isy/street-zustand.xml" \
  --risk-table "$tmp/bad-table.json"
# info --profile shows what the findings cut off.
expect 0 '"cut_off_by_findings"' -- \
  "$sp" info --profile makro-plus --json "$isybau" --condition "$isy/street-zustand.xml"

# Generated networks are deterministic and valid.
expect 0 'wrote' -- "$sp" generate --manholes 500 --seed 3 -o "$tmp/g1.json"
expect 0 'wrote' -- "$sp" generate --manholes 500 --seed 3 -o "$tmp/g2.json"
if cmp -s "$tmp/g1.json" "$tmp/g2.json"; then passed=$((passed + 1)); else
  echo "FAIL: the same seed gave different networks"; failures=$((failures + 1)); fi
expect 0 'valid \(500 manholes' -- "$sp" validate --map "$tmp/g1.json"
expect 2 'manholes' -- "$sp" generate --manholes 3 -o "$tmp/g3.json"
for spread in uniform clustered near-exit; do  # issue 16: missions of every shape
  expect 0 '5 tasks' -- "$sp" generate --manholes 500 --seed 3 -o "$tmp/g4.json" --mission-tasks 5 \
    --mission-out "$tmp/m-$spread.json" --mission-spread "$spread"
done
expect 2 'unknown spread' -- "$sp" generate --manholes 500 -o "$tmp/g4.json" --mission-tasks 5 \
  --mission-out "$tmp/m-x.json" --mission-spread everywhere
expect 0 'exact tour search' -- "$sp" plan --select-goals -a exact --map "$tmp/g4.json" --mission "$tmp/m-uniform.json"

# Plans: the paper's (invalid at step 11), its correction, FF and Fast Downward forms, bad lines.
plans=$src/datasets/ais-testbed/plans
check=("$sp" check --map "$ais" --mission "$mission")
expect 0 '^valid: 14 steps, 585\.4 s, 19\.5 Wh$' -- "${check[@]}" "$plans/paper-corrected.plan"
expect 1 '^invalid: step 11 \(INSPECT_PIPE P4\): the robot is at M5 slot 4 \(P4\), not in pipe P4$' -- \
  "${check[@]}" "$plans/paper-section-6.plan"
head -n 9 "$plans/paper-corrected.plan" > "$tmp/short.plan"
expect 1 "invalid: goal not reached: task 'inspect' \(inspect_pipe\) is not done" -- \
  "${check[@]}" "$tmp/short.plan"
printf 'DRIVE_PIPE_TO_MANHOLE P12 M2\nDRIVE_PIPE_TO_MANHOLE P99 M2\n' > "$tmp/bad.plan"
expect 1 "bad.plan:2: error: unknown pipe 'P99'" -- "${check[@]}" "$tmp/bad.plan"
expect 1 '"valid": false' -- "${check[@]}" "$tmp/bad.plan" --json
sed 's/.*/(\L&)/' "$plans/paper-corrected.plan" > "$tmp/fd.plan"
echo '; cost = 585 (general cost)' >> "$tmp/fd.plan"
expect 0 '^valid: 14 steps' -- "${check[@]}" "$tmp/fd.plan"
awk '{ printf "%s%5d: %s\n", (NR == 1 ? "step " : "     "), NR - 1, $0 }' \
  "$plans/paper-corrected.plan" > "$tmp/ff.plan"
expect 0 '^valid: 14 steps' -- "${check[@]}" "$tmp/ff.plan"
expect 0 '"action": "INSPECT_PIPE P4"' -- "${check[@]}" "$plans/paper-corrected.plan" --json
expect 1 '"failed_step": 11' -- "${check[@]}" "$plans/paper-section-6.plan" --json
expect 3 'cannot read .*missing.plan' -- "${check[@]}" "$tmp/missing.plan"
expect 2 'mission' -- "$sp" check --map "$ais" "$plans/paper-corrected.plan"

# Planning: the paper's mission gives the paper's route; plans round-trip through check.
plans=$src/datasets/ais-testbed/plans
if "$sp" plan --map "$ais" --mission "$mission" -q > "$tmp/plan.txt" && cmp -s "$tmp/plan.txt" "$plans/paper-corrected.plan"; then
  passed=$((passed + 1))
else
  echo "FAIL: sewerplan plan on the paper's mission differs from $plans/paper-corrected.plan"
  diff "$tmp/plan.txt" "$plans/paper-corrected.plan" | head; failures=$((failures + 1))
fi
expect 0 'plan: 14 steps, 585.4 s, 19.5 Wh \(optimal\)' -- "$sp" plan --map "$ais" --mission "$mission" -o "$tmp/p.plan"
expect 0 'valid: 14 steps' -- "$sp" check --map "$ais" --mission "$mission" "$tmp/p.plan"
for a in ehc gbfs wastar astar; do
  "$sp" plan --map "$ais" --mission "$mission" -a "$a" -q -o "$tmp/$a.plan" > /dev/null 2>&1
  expect 0 'valid' -- "$sp" check --map "$ais" --mission "$mission" "$tmp/$a.plan"
done
expect 0 '"cost_s"' -- "$sp" plan --map "$ais" --mission "$mission" --json
cat > "$tmp/cut.json" <<'JSON'
{"format": "sewerplan-mission", "version": 1, "start": {"pipe": "P12"},
 "tasks": [{"name": "far", "type": "inspect_pipe", "pipe": "P4"}],
 "closed": {"pipes": ["P10", "P13", "P8", "P3"],
            "passages": [{"manhole": "M6", "from_slot": 3, "to_slot": 2},
                         {"manhole": "M6", "from_slot": 4, "to_slot": 2}]}}
JSON
expect 4 "task 'far' \(inspect_pipe\): no route from the start" -- "$sp" plan --map "$ais" --mission "$tmp/cut.json"
expect 2 'unknown' -- "$sp" plan --map "$ais" --mission "$mission" -a dijkstra
expect 0 "dropped task 'far': no route" -- "$sp" plan --map "$ais" --mission "$tmp/cut.json" --select-goals
# check reads what plan --select-goals wrote, against the same mission (it said: task not done).
"$sp" plan --map "$ais" --mission "$tmp/cut.json" --select-goals -q -o "$tmp/selected.plan" > /dev/null 2>&1
expect 0 "left out: task 'far'" -- "$sp" check --map "$ais" --mission "$tmp/cut.json" --select-goals "$tmp/selected.plan"
expect 1 "task 'far' .* is not done" -- "$sp" check --map "$ais" --mission "$tmp/cut.json" "$tmp/selected.plan"
# A pipe of 1e16 m passed validate and stopped plan on an internal check (exit 134).
sed 's/"length_m": 8.485/"length_m": 1e16/' "$ais" > "$tmp/huge.json"
expect 1 'length must be at most 100000 m, got 1e\+16' -- "$sp" validate --map "$tmp/huge.json"
expect 1 'length must be at most' -- "$sp" plan --map "$tmp/huge.json" --mission "$mission"

# simulate: the paper's mission with an obstacle the head lift clears and one in the inspected pipe.
expect 0 'mission ended at pipe P9' -- "$sp" simulate --map "$ais" --mission "$mission" --faults "$src/datasets/ais-testbed/faults/demo.json" --log "$tmp/events.jsonl" -q
expect 0 '"type":"replan","reason":"blockage in P4 at 4.95 m"' -- cat "$tmp/events.jsonl"
expect 0 'phase=2: lift the head and retry ok=yes' -- "$sp" simulate --map "$ais" --mission "$mission" --faults "$src/datasets/ais-testbed/faults/demo.json"
expect 1 'cut.json' -- "$sp" simulate --map "$ais" --mission "$mission" --faults "$tmp/cut.json"
echo '{"format": "sewerplan-faults", "version": 1, "malfunctions": [{"at_job": 2, "kind": "permanent"}]}' > "$tmp/stuck.json"
expect 4 'beacon on: the robot cannot move' -- "$sp" simulate --map "$ais" --mission "$mission" --faults "$tmp/stuck.json" -q
echo '{"format": "sewerplan-recovery", "version": 1, "malfunction": [{"manoeuvre": "reboot", "tries": -1}]}' > "$tmp/recovery.json"
expect 1 'recovery.json:\$\.malfunction\[0\]\.tries: error: expected a whole number from 0 to 1000, got -1' -- "$sp" simulate --map "$ais" --mission "$mission" --recovery "$tmp/recovery.json" -q
# The profile is the policy: without the lift row the demo's lift-only obstacle stays.
echo '{"format": "sewerplan-recovery", "version": 1, "blockage": [{"manoeuvre": "back-up", "tries": 2, "distance_m": 0.05}]}' > "$tmp/no-lift.json"
expect 0 '' -- "$sp" simulate --map "$ais" --mission "$mission" --faults "$src/datasets/ais-testbed/faults/demo.json" --recovery "$tmp/no-lift.json" --log "$tmp/no-lift.jsonl" -q
expect 0 '"type":"replan","reason":"blockage in P1 at' -- cat "$tmp/no-lift.jsonl"
expect 0 'phase=2: lift the head and retry ok=yes' -- "$sp" simulate --map "$ais" --mission "$mission" --faults "$src/datasets/ais-testbed/faults/demo.json" --recovery "$src/datasets/recovery/default.json"
expect 2 'random-faults' -- "$sp" simulate --map "$ais" --mission "$mission" --faults "$tmp/stuck.json" --random-faults 3
# A fault file with a bad value is invalid input (1), as the docs say, not a usage error.
echo '{"format": "sewerplan-faults", "version": 1, "obstacles": [{"pipe": "P99", "offset_m": 1}]}' > "$tmp/bad-faults.json"
expect 1 'P99' -- "$sp" simulate --map "$ais" --mission "$mission" --faults "$tmp/bad-faults.json" -q
# Unbounded drawing (47 s and 6 GB): a rate beyond the limit is refused at once.
expect 2 'obstacle_rate_per_km must be at most 1000' -- "$sp" simulate --map "$ais" --mission "$mission" --random-faults 1,1e9 -q
# --world-errors (docs/simulation.md): a bad spec is a usage error naming the item; "none" is the
# simulator as before (the same log, byte for byte); a realistic world runs, whatever it meets.
expect 2 "--world-errors: unknown profile 'realism' \\(known: none, realistic\\)" -- "$sp" simulate --map "$ais" --mission "$mission" --world-errors realism -q
expect 2 "--world-errors: 'dirft=0.1': unknown key" -- "$sp" simulate --map "$ais" --mission "$mission" --world-errors realistic,dirft=0.1 -q
expect 2 "--world-errors: 'lengths=1.5': must be from 0 to 1" -- "$sp" campaign --map "$ais" --mission "$mission" --runs 2 --world-errors lengths=1.5
expect 2 "--world-errors: 'drift=x': not a number" -- "$sp" campaign --map "$ais" --mission "$mission" --runs 2 --world-errors realistic,drift=x
"$sp" simulate --map "$ais" --mission "$mission" --random-faults 3 --log "$tmp/plain.jsonl" -q >/dev/null 2>&1
"$sp" simulate --map "$ais" --mission "$mission" --random-faults 3 --world-errors none --log "$tmp/none.jsonl" -q >/dev/null 2>&1
# (planning_ms is measured, the rest must be equal)
expect 0 '' -- bash -c "cmp <(sed -E 's/\"planning_ms\":[^,]*,//' \"$tmp/plain.jsonl\") <(sed -E 's/\"planning_ms\":[^,]*,//' \"$tmp/none.jsonl\")"
expect 0 '' -- bash -c "\"$sp\" simulate --map \"$ais\" --mission \"$mission\" --world-errors realistic --world-seed 4 -q; r=\$?; [ \$r -eq 0 ] || [ \$r -eq 4 ]"
expect 0 '"seeded":\[\{"kind":' -- "$sp" campaign --map "$ais" --mission "$mission" --runs 3 --seed 2 --only 1 --world-errors realistic,lengths=1
# --learnt: the blockage the first mission met is known to the second, which plans around it.
expect 0 'mission ended' -- "$sp" simulate --map "$ais" --mission "$mission" --faults "$src/datasets/ais-testbed/faults/blocked-p5.json" --learnt "$tmp/learnt.json" -q
expect 0 '"pipe": "P5"' -- cat "$tmp/learnt.json"
expect 0 ', 0 replans' -- "$sp" simulate --map "$ais" --mission "$mission" --faults "$src/datasets/ais-testbed/faults/blocked-p5.json" --learnt "$tmp/learnt.json" -q
echo '{"format": "sewerplan-learnt", "version": 1, "blockages": [{"pipe": "PX", "offset_m": 1}]}' > "$tmp/bad-learnt.json"
expect 1 'bad-learnt.json:\$\.blockages\[0\]\.pipe: error: unknown pipe "PX"' -- "$sp" simulate --map "$ais" --mission "$mission" --learnt "$tmp/bad-learnt.json" -q
# The localisation's memory of the pipes (issue 29): the manholes the map lacks that it became
# confident of are saved with what the robot learnt, and a second mission starts from them (the
# same three junctions, each now seen twice); a bad entry is an error naming it.
expect 0 'mission ended' -- "$sp" simulate --map "$ais" --mission "$mission" --world-errors junctions=0.5 --world-seed 3 --learnt "$tmp/junctions.json" -q
expect 0 '"sightings": 1' -- cat "$tmp/junctions.json"
expect 0 'mission ended' -- "$sp" simulate --map "$ais" --mission "$mission" --world-errors junctions=0.5 --world-seed 3 --learnt "$tmp/junctions.json" -q
expect 0 '^3$' -- grep -c '"sightings": 2' "$tmp/junctions.json"
echo '{"format": "sewerplan-learnt", "version": 3, "junction_memory": {"junctions": [{"pipe": "P4", "from_end": "up", "distance_m": 1, "sd_m": 0.1, "sightings": 1}]}}' > "$tmp/bad-junction.json"
expect 1 'bad-junction.json:\$\.junction_memory\.junctions\[0\]\.from_end: error: expected "from" or "to"' -- "$sp" simulate --map "$ais" --mission "$mission" --learnt "$tmp/bad-junction.json" -q
# Hazards passed safely learn (issue 34): each update is a hazard event of the live log, and the
# learnt file keeps the probabilities; one outside 0..1 is an error naming the entry.
battery_trap=$src/datasets/condition/battery-trap
expect 0 'hazard +pipe=[^ ]+ offset_m=[0-9.]+ reason=.* observed=passed probability_before=' -- "$sp" simulate --map "$battery_trap/map.json" --mission "$battery_trap/mission.json" --risk expected --learnt "$tmp/trap-learnt.json"
expect 0 '"passes": 1' -- cat "$tmp/trap-learnt.json"
expect 0 'mission ended' -- "$sp" simulate --map "$battery_trap/map.json" --mission "$battery_trap/mission.json" --risk expected --learnt "$tmp/trap-learnt.json" -q
echo '{"format": "sewerplan-learnt", "version": 2, "hazards": [{"pipe": "P4", "offset_m": 1, "reason": "BBA roots", "probability": 1.5, "passes": 0, "blocked": false}]}' > "$tmp/bad-hazard.json"
expect 1 'bad-hazard.json:\$\.hazards\[0\]\.probability: error: expected a probability from 0 to 1, got 1.5' -- "$sp" simulate --map "$ais" --mission "$mission" --learnt "$tmp/bad-hazard.json" -q

# PDDL round trip: export, then read back what FF and Fast Downward print for it.
expect 0 'wrote .*domain.pddl and .*problem.pddl' -- "$sp" export-pddl --map "$ais" --mission "$mission" --out "$tmp/pddl"
expect 0 '\(:action DRIVE_MANHOLE_TYPE_4_FROM_3_TO_4' -- cat "$tmp/pddl/domain.pddl"
expect 0 'with action costs' -- "$sp" export-pddl --map "$ais" --mission "$mission" --out "$tmp/pddl-costs" --action-costs
expect 0 'total-cost' -- cat "$tmp/pddl-costs/problem.pddl"
tr '[:upper:]' '[:lower:]' < "$src/datasets/ais-testbed/plans/paper-corrected.plan" | grep -v '^[;#]' |
  sed -E 's/^(.+)$/(\1)/' > "$tmp/sas_plan"
echo '; cost = 585383 (general cost)' >> "$tmp/sas_plan"
run_once "$sp" import-plan --format fd --map "$ais" --mission "$mission" "$tmp/sas_plan"
expect_ran 0 'valid: 14 steps, 585.4 s'
expect_ran 0 'DRIVE_PIPE_TO_MANHOLE P12 M2'
printf 'ff: found legal plan as follows\n\nstep    0: DRIVE_PIPE_TO_MANHOLE P12 M2\n        1: DRIVE_PIPE_TO_MANHOLE P99 M2\n' > "$tmp/ff.out"
expect 1 "ff.out:4: error: unknown object 'P99'" -- "$sp" import-plan --format ff --map "$ais" --mission "$mission" "$tmp/ff.out"
printf '(drive_pipe_to_manhole p12 m2)\n' > "$tmp/short_plan"
expect 1 'invalid: goal not reached' -- "$sp" import-plan --format fd --map "$ais" --mission "$mission" "$tmp/short_plan"
expect 2 "unknown planner output 'lpg'" -- "$sp" import-plan --format lpg --map "$ais" --mission "$mission" "$tmp/short_plan"
: > "$tmp/empty_ff.out"  # issue 16: an empty FF output is not an empty plan
expect 1 'holds no FF plan' -- "$sp" import-plan --format ff --map "$ais" --mission "$mission" "$tmp/empty_ff.out"

# campaign: runs, the guard, --only, shards and merge (docs/campaign.md).
expect 0 'Verdict: clean' -- "$sp" campaign --map "$ais" --mission "$mission" --runs 12 --seed 5 --jobs 2 -o "$tmp/camp"
expect 0 'tasks vs oracle, mean' -- cat "$tmp/camp/summary.md"
expect 0 '<g id="histogram">' -- cat "$tmp/camp/summary.svg"
line7=$(sed -n 8p "$tmp/camp/runs.jsonl" | sed 's/,"measured".*//')
expect 0 "^${line7//[/\\[}" -- bash -c "\"$sp\" campaign --map \"$ais\" --mission \"$mission\" --runs 12 --seed 5 --only 7 | sed 's/,\"measured\".*//'"
for i in 0 1 2; do
  expect 0 '' -- "$sp" campaign --map "$ais" --mission "$mission" --runs 12 --seed 5 --shard $i/3 -o "$tmp/shard$i" -q
done
expect 0 'Verdict: clean' -- "$sp" campaign merge "$tmp/shard0" "$tmp/shard1" "$tmp/shard2" -o "$tmp/merged"
expect 0 '' -- bash -c "diff <(sed 's/,\"measured\".*//' \"$tmp/camp/runs.jsonl\") <(sed 's/,\"measured\".*//' \"$tmp/merged/runs.jsonl\")"
# merge -q, like the campaign itself: nothing on the terminal, the same files written.
expect 0 '' -- bash -c 'out=$("$@" 2>&1) && [ -z "$out" ]' - \
  "$sp" campaign merge "$tmp/shard0" "$tmp/shard1" "$tmp/shard2" -o "$tmp/merged-q" -q
expect 0 '' -- cmp "$tmp/merged/summary.json" "$tmp/merged-q/summary.json"
# Issue 14: a go-to at P9's M10 end leaves the robot right at that end after a pass into P9; the
# drive of 0 m back to M10 must bring it to the mouth (it stayed in P9, and was "ended at exit M10").
cat >"$tmp/end-of-p9.json" <<'JSON'
{"format": "sewerplan-mission", "version": 1, "name": "go-to-the-end-of-p9", "profile": "makro-1.1",
 "start": {"pipe": "P12"}, "battery_reserve": 0.2,
 "tasks": [{"name": "end", "type": "go_to", "at": {"pipe": "P9", "offset_m": 4.243}}]}
JSON
expect 0 'could reach an exit but did not \| 0 \| 0 \|' -- "$sp" campaign --map "$ais" --mission "$tmp/end-of-p9.json" --runs 12 --seed 5
# --planner-time-limit: every replan reaches a 1 us limit and still heads for an exit, never the beacon.
expect 0 'planner time limit 1e-06 s' -- "$sp" campaign --map "$ais" --mission "$mission" --runs 6 --seed 5 --planner-time-limit 0.000001 -o "$tmp/limit"
expect 0 'beacons: limit \| 0 \| 0 \|' -- cat "$tmp/limit/summary.md"
expect 0 'could reach an exit but did not \| 0 \| 0 \|' -- cat "$tmp/limit/summary.md"
expect 0 '"planner_time_limit_s": 1e-06' -- cat "$tmp/limit/campaign.json"
expect 2 'planner-time-limit: Value -1 not in range' -- "$sp" campaign --map "$ais" --mission "$mission" --planner-time-limit -1
expect 1 'shard\(s\) 1 of 3 missing' -- "$sp" campaign merge "$tmp/shard0" "$tmp/shard2" -o "$tmp/merged2"
expect 1 'shard 2/3 given twice' -- "$sp" campaign merge "$tmp/shard0" "$tmp/shard1" "$tmp/shard2" "$tmp/shard2" -o "$tmp/merged3"
# A hung run costs the campaign its --timeout: 3 s, thrice the slowest other run in a loaded ASan
# build (the injected crash, whose sanitizer report takes 0.9 s).
expect 6 'run 3 \(seed [0-9]+\): crash.*--only 3' -- env SEWERPLAN_CAMPAIGN_INJECT=crash:3,hang:4 "$sp" campaign --map "$ais" --mission "$mission" --runs 6 --timeout 3 --jobs 2
expect 6 'run 4 \(seed [0-9]+\): hang' -- env SEWERPLAN_CAMPAIGN_INJECT=hang:4 "$sp" campaign --map "$ais" --mission "$mission" --runs 6 --timeout 3
expect 2 "fault-rates: 'rain=1': unknown rate" -- "$sp" campaign --map "$ais" --mission "$mission" --fault-rates rain=1
expect 2 "shard: expected I/N" -- "$sp" campaign --map "$ais" --mission "$mission" --shard 3/3
expect 2 'map and --mission are required' -- "$sp" campaign --runs 3

# render: the network, the plan and a simulated run's log, as SVG.
expect 0 'wrote .*demo.svg' -- "$sp" render --map "$ais" --mission "$mission" --plan "$src/datasets/ais-testbed/plans/paper-corrected.plan" --log "$tmp/events.jsonl" --faults "$src/datasets/ais-testbed/faults/demo.json" -o "$tmp/demo.svg"
expect 0 '<polyline id="driven"' -- cat "$tmp/demo.svg"
expect 0 'class="blocked"' -- cat "$tmp/demo.svg"
echo 'not json' > "$tmp/bad.jsonl"
expect 1 'bad.jsonl:1: error: not a JSON object' -- "$sp" render --map "$ais" --mission "$mission" --log "$tmp/bad.jsonl" -o "$tmp/bad.svg"
expect 2 "need --mission" -- "$sp" render --map "$ais" --log "$tmp/events.jsonl" -o "$tmp/x.svg"
# The picture's format is -o's extension: .svg or .png in any case, SVG without one; any other
# extension is refused before the map is read (it wrote SVG into x.pdf), and nothing is written.
expect 2 "render -o $tmp/x.pdf: unknown extension \".pdf\" \(.svg or .png\)" -- \
  "$sp" render --map "$ais" -o "$tmp/x.pdf"
expect 2 'unknown extension' -- "$sp" render --map "$tmp/no-such-map.json" -o "$tmp/x.svgz"
expect 0 '' -- test ! -e "$tmp/x.pdf" -a ! -e "$tmp/x.svgz"
expect 2 '"code": "usage", *"exit_code": 2, *"message": "render -o [^"]*x.jpg: unknown extension' -- bash -c "set -o pipefail; '$sp' render --map '$ais' -o '$tmp/x.jpg' --json | tr -d '\n'"
expect 0 '"format": "svg"' -- "$sp" render --map "$ais" -o "$tmp/CAPS.SVG" --json
expect 0 '"format": "svg"' -- "$sp" render --map "$ais" -o "$tmp/no-extension" --json
expect 0 '^<svg' -- head -c 4 "$tmp/no-extension"
# export-geojson writes GeoJSON only: a GeoPackage or Shapefile name is refused, not filled with it.
if grep -q export-geojson <<<"$help_out"; then
  expect 2 "export-geojson -o $tmp/x.gpkg: unknown extension \".gpkg\" \(.geojson or .json\)" -- \
    "$sp" export-geojson --map "$ais" --crs EPSG:25832 -o "$tmp/x.gpkg"
  expect 2 "--nav2 $tmp/g.shp: unknown extension" -- \
    "$sp" export-geojson --map "$ais" --crs EPSG:25832 --nav2 "$tmp/g.shp"
  expect 0 '' -- test ! -e "$tmp/x.gpkg" -a ! -e "$tmp/g.shp"
fi
# Manhole motions (docs/motion.md): precompute beside a copy of the map; plan uses the table and
# says so; --no-motion and a stale table. A build without OMPL says it cannot plan them.
mkdir -p "$tmp/motion"
cp "$ais" "$tmp/motion/map.json"
run_once "$sp" motion precompute --map "$tmp/motion/map.json" --seed 3
if grep -q 'has no OMPL' <<<"$ran_out"; then
  expect_ran 1 'this build of sewerplan has no OMPL'
else
  expect_ran 0 'motion: 50 passages, [0-9]+ geometries, [0-9]+ feasible; motion rejects'
  expect 0 'wrote .*/motion/map.motion.json' -- "$sp" motion precompute --map "$tmp/motion/map.json" -q
  # A time limit that has passed before the first passage: no table, exit 5.
  expect 5 'time limit' -- "$sp" motion precompute --map "$tmp/motion/map.json" -q \
    --time-limit 1e-9 -o "$tmp/motion/limited.motion.json"
  if [ -e "$tmp/motion/limited.motion.json" ]; then
    echo "FAIL: motion precompute --time-limit wrote a table"; failures=$((failures + 1))
  fi
  expect 2 'time-limit' -- "$sp" motion precompute --map "$tmp/motion/map.json" --time-limit -1
  expect 0 'motion: using 50 planned manhole passages from .*map.motion.json' -- \
    "$sp" plan --map "$tmp/motion/map.json" --mission "$mission"
  expect 0 'plan: 14 steps, 585.4 s' -- \
    "$sp" plan --map "$tmp/motion/map.json" --mission "$mission" --no-motion
  "$sp" plan --map "$tmp/motion/map.json" --mission "$mission" -q -o "$tmp/motion/plan.txt" 2>/dev/null
  expect 0 'valid: 14 steps' -- \
    "$sp" check --map "$tmp/motion/map.json" --mission "$mission" "$tmp/motion/plan.txt"
  echo '{"base": "makro-1.1", "name": "long", "length_m": 2.4}' > "$tmp/motion/long.json"
  "$sp" motion precompute --map "$tmp/motion/map.json" -q --profile "$tmp/motion/long.json" \
    -o "$tmp/motion/long.motion.json" >/dev/null
  expect 0 'motion: using 50' -- \
    "$sp" simulate --map "$tmp/motion/map.json" --mission "$mission" -q
  expect 0 'motion: using 50' -- \
    "$sp" campaign --map "$tmp/motion/map.json" --mission "$mission" --runs 4 -q
  # A campaign made with the table is another campaign than one without it: shards do not merge.
  "$sp" campaign --map "$tmp/motion/map.json" --mission "$mission" --runs 4 --shard 0/2 -q \
    -o "$tmp/motion/s0" 2>/dev/null
  "$sp" campaign --map "$tmp/motion/map.json" --mission "$mission" --runs 4 --shard 1/2 -q \
    --no-motion -o "$tmp/motion/s1" 2>/dev/null
  expect 1 'the mission differs' -- \
    "$sp" campaign merge "$tmp/motion/s0" "$tmp/motion/s1" -o "$tmp/motion/merged"
  expect 1 'stale motion table: it was made for another robot geometry' -- \
    "$sp" plan --map "$tmp/motion/map.json" --mission "$mission" --motion "$tmp/motion/long.motion.json"
  expect 3 'cannot read' -- \
    "$sp" plan --map "$tmp/motion/map.json" --mission "$mission" --motion "$tmp/motion/none.json"
fi

# serve applies --gis-fields to its GIS maps; with none among them the mapping would be ignored
# silently, so it is a usage error before the server starts.
expect 2 'serve: --gis-fields .*: none of the maps is a GIS source' -- \
  timeout 20 "$sp" serve --map "$ais" --gis-fields "$tmp/fields-for-nothing.json" --port 0

echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
