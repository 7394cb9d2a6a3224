#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Every command's --json (docs/cli.md, "JSON output"): run on the AIS test environment, the output
# must parse as one JSON document and hold the documented fields, failures the shared error shape
# ({"error": {"code", "exit_code", "message", "diagnostics"}}) with the right exit code.
# Usage: json_test.sh PATH_TO_SEWERPLAN SOURCE_DIR
set -uo pipefail
sp=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
passed=0

# json CODE 'PYTHON CHECK' -- COMMAND...: runs COMMAND, wants exit CODE, keeps its standard output
# to be parsed as JSON (bound to j) and the check evaluated on it; each check is an assert-free
# boolean expression. The exit code is checked at once; the JSON checks all at the end, in one
# Python process (a Python start costs 0.1 to 0.4 s, more than most of the commands).
checks=0
json() {
  local code=$1 check=$2
  shift 3
  "$@" > "$tmp/out.json" 2> "$tmp/err.txt"
  local got=$?
  if [ "$got" -ne "$code" ]; then
    echo "FAIL: $* -> exit $got (want $code)"; head -5 "$tmp/err.txt"; failures=$((failures + 1))
    return
  fi
  checks=$((checks + 1))
  mv "$tmp/out.json" "$tmp/out-$checks.json"
  printf '%s' "$check" > "$tmp/check-$checks.py"
  printf '%s' "$*" > "$tmp/command-$checks.txt"
}

# Evaluates the checks json() kept; prints each failure and, last, the number that passed.
check_all() {
  python3 - "$tmp" "$checks" <<'PY'
import json, sys
tmp, n = sys.argv[1], int(sys.argv[2])
ok = 0
for i in range(1, n + 1):
    check = open(f"{tmp}/check-{i}.py").read()
    command = open(f"{tmp}/command-{i}.txt").read()
    text = open(f"{tmp}/out-{i}.json").read()
    try:
        j = json.loads(text)
    except ValueError as e:
        print(f"FAIL: {command}\nnot JSON: {e}\n{text[:400]}")
        continue
    try:
        good = eval(check, {"j": j})
    except Exception as e:  # a field missing or of another type fails this check, not the rest
        good, why = False, f"{type(e).__name__}: {e}"
    else:
        why = "check failed"
    if not good:
        print(f"FAIL: {command}\n{why}: {check}\n{json.dumps(j)[:600]}")
        continue
    ok += 1
print(ok)
PY
}

# The error shape every failure shares, with its code name and exit code.
err() { echo "set(j['error']) >= {'code', 'exit_code', 'message', 'diagnostics'} and j['error']['code'] == '$1' and j['error']['exit_code'] == $2"; }

ais=$src/datasets/ais-testbed/map.json
mission=$src/datasets/ais-testbed/missions/paper.json
plans=$src/datasets/ais-testbed/plans

# validate, info, convert, generate
json 0 "j['valid'] is True and j['manholes'] == 12 and j['pipes'] == 14 and j['errors'] == [] and 'warnings' in j" -- \
  "$sp" validate --map "$ais" --mission "$mission" --json
json 1 "j['valid'] is False and $(err invalid-map 1) and j['error']['file'].endswith('broken.json') and j['error']['path'].startswith('\$.') and j['errors']" -- \
  "$sp" validate --map "$src/tests/data/json/broken.json" --json
json 3 "$(err io 3)" -- "$sp" info --map "$tmp/missing.json" --json
json 0 "j['manholes'] == 12 and j['pipes'] == 14 and set(j) >= {'name', 'total_length_m', 'exits', 'findings', 'memory_bytes'}" -- \
  "$sp" info --map "$ais" --json
json 0 "set(j['driveability']) >= {'profile', 'too_narrow', 'too_wide', 'passages', 'reachable', 'closed_by_findings'}" -- \
  "$sp" info --map "$ais" --profile makro-plus --json
json 2 "$(err usage 2) and 'needs --profile' in j['error']['message']" -- "$sp" info --map "$ais" --start M1 --json
json 0 "j['wrote'].endswith('a.sewer') and j['manholes'] == 12 and j['pipes'] == 14 and j['findings'] == 0" -- \
  "$sp" convert --map "$ais" -o "$tmp/a.sewer" --json
json 2 "$(err usage 2)" -- "$sp" convert --map "$ais" -o "$tmp/x.out" --to xml --json
json 0 "j['map']['manholes'] == 30 and j['map']['topology'] == 'tree' and j['map']['seed'] == 4 and j['mission']['tasks'] == 2 and j['mission']['wrote'].endswith('g-m.json')" -- \
  "$sp" generate --manholes 30 --seed 4 -o "$tmp/g.json" --mission-tasks 2 --mission-out "$tmp/g-m.json" --json

# plan: the plan with its decision and statistics; an impossible mission: the error, the
# Replanner's decision and the tasks it would drop, with reasons
json 0 "j['format'] == 'sewerplan-plan' and j['valid'] and len(j['steps']) == 14 and j['decision'] == 'follow-plan' and j['optimal'] is True and j['dropped'] == [] and j['statistics']['search']['expanded'] >= 0 and 'keys' in j['statistics']['compile'] and abs(j['cost_s'] - 585.383) < 0.01 and j['algorithm']" -- \
  "$sp" plan --map "$ais" --mission "$mission" --json -q
cat > "$tmp/cut.json" <<'JSON'
{"format": "sewerplan-mission", "version": 1, "start": {"pipe": "P12"},
 "tasks": [{"name": "far", "type": "inspect_pipe", "pipe": "P4"}],
 "closed": {"pipes": ["P10", "P13", "P8", "P3"],
            "passages": [{"manhole": "M6", "from_slot": 3, "to_slot": 2},
                         {"manhole": "M6", "from_slot": 4, "to_slot": 2}]}}
JSON
json 4 "$(err no-plan 4) and 'far' in j['error']['message'] and j['decision'] == 'degraded' and j['dropped'][0]['task'] == 'far' and 'no route' in j['dropped'][0]['reason'] and j['statistics']['time_s'] >= 0 and 'end' in j['fallback']" -- \
  "$sp" plan --map "$ais" --mission "$tmp/cut.json" --json
json 0 "j['decision'] == 'degraded' and j['dropped'][0]['task'] == 'far' and j['valid']" -- \
  "$sp" plan --map "$ais" --mission "$tmp/cut.json" --select-goals --json -q
json 2 "$(err usage 2) and 'dijkstra' in j['error']['message']" -- "$sp" plan --map "$ais" --mission "$mission" -a dijkstra --json
json 2 "$(err usage 2)" -- "$sp" plan --mission "$mission" --json

# check and import-plan: the plan JSON and the verdict
json 0 "j['valid'] and j['decision'] == 'follow-plan' and j['left_out'] == [] and len(j['steps']) == 14" -- \
  "$sp" check --map "$ais" --mission "$mission" "$plans/paper-corrected.plan" --json
json 1 "j['valid'] is False and $(err invalid-plan 1) and j['failed_step'] == 11" -- \
  "$sp" check --map "$ais" --mission "$mission" "$plans/paper-section-6.plan" --json
json 3 "j['valid'] is False and $(err io 3)" -- "$sp" check --map "$ais" --mission "$mission" "$tmp/none.plan" --json
json 0 "j['domain'].endswith('domain.pddl') and j['problem'].endswith('problem.pddl') and j['action_costs'] is False" -- \
  "$sp" export-pddl --map "$ais" --mission "$mission" --out "$tmp/pddl" --json
tr '[:upper:]' '[:lower:]' < "$plans/paper-corrected.plan" | grep -v '^[;#]' | sed -E 's/^(.+)$/(\1)/' > "$tmp/sas_plan"
json 0 "j['valid'] and len(j['steps']) == 14" -- \
  "$sp" import-plan --format fd --map "$ais" --mission "$mission" "$tmp/sas_plan" --json
printf 'ff: found legal plan as follows\n\nstep    0: DRIVE_PIPE_TO_MANHOLE P12 M2\n        1: DRIVE_PIPE_TO_MANHOLE P99 M2\n' > "$tmp/ff.out"
json 1 "$(err parse 1) and j['error']['line'] == 4" -- \
  "$sp" import-plan --format ff --map "$ais" --mission "$mission" "$tmp/ff.out" --json

# simulate: the mission report
json 0 "j['outcome'] == 'ended' and j['decision'] in ('follow-plan', 'degraded') and j['beacon_cause'] == 'none' and j['replans'] >= 1 and j['tasks_done'] and isinstance(j['dropped'], list) and j['time_s'] > 0 and j['energy_wh'] > 0 and j['battery_reserve_kept'] is True" -- \
  "$sp" simulate --map "$ais" --mission "$mission" --faults "$src/datasets/ais-testbed/faults/demo.json" --json
echo '{"format": "sewerplan-faults", "version": 1, "malfunctions": [{"at_job": 2, "kind": "permanent"}]}' > "$tmp/stuck.json"
json 4 "j['outcome'] == 'beacon' and j['decision'] == 'stuck' and j['beacon_cause'] in ('malfunction', 'stuck')" -- \
  "$sp" simulate --map "$ais" --mission "$mission" --faults "$tmp/stuck.json" --json
echo '{"format": "sewerplan-faults", "version": 1, "obstacles": [{"pipe": "P99", "offset_m": 1}]}' > "$tmp/bad-faults.json"
json 1 "j['error']['exit_code'] == 1 and j['error']['diagnostics']" -- \
  "$sp" simulate --map "$ais" --mission "$mission" --faults "$tmp/bad-faults.json" --json

# campaign: the summary (summary.json); --only: the run's line
json 0 "j['runs'] == 2 and set(j) >= {'completed', 'crashes', 'hangs', 'ours', 'baseline', 'clean'} and j['clean'] is True" -- \
  "$sp" campaign --map "$ais" --mission "$mission" --runs 2 --seed 1 --json
json 0 "j['run'] == 1 and 'status' in j" -- "$sp" campaign --map "$ais" --mission "$mission" --runs 2 --only 1 --json
json 2 "$(err usage 2)" -- "$sp" campaign --map "$ais" --runs 2 --json

# render, motion precompute
json 0 "j['wrote'].endswith('r.svg') and j['format'] == 'svg' and j['mission'].endswith('paper.json')" -- \
  "$sp" render --map "$ais" --mission "$mission" -o "$tmp/r.svg" --json
json 2 "$(err usage 2)" -- "$sp" render --map "$ais" --plan x -o "$tmp/r.svg" --json
mkdir -p "$tmp/motion" && cp "$ais" "$tmp/motion/map.json"
if "$sp" motion precompute --map "$tmp/motion/map.json" -q > /dev/null 2>&1; then
  json 0 "j['wrote'].endswith('map.motion.json') and j['passages'] > 0 and j['feasible'] <= j['passages'] and j['profile'] == 'makro-1.1'" -- \
    "$sp" motion precompute --map "$tmp/motion/map.json" -q --json
else
  json 1 "$(err unsupported-format 1)" -- "$sp" motion precompute --map "$tmp/motion/map.json" --json
fi

# index build (docs/formats/route-index.md): the summary; a stale index is invalid input.
json 0 "j['wrote'].endswith('map.route-index.bin') and j['nodes'] > 0 and j['bytes'] > 64 and len(j['fingerprint']) == 16 and j['profile'] == 'makro-1.1'" -- \
  "$sp" index build --map "$tmp/motion/map.json" --no-motion --json
"$sp" index build --map "$tmp/motion/map.json" --no-motion --profile makro-plus -o "$tmp/plus.bin" >/dev/null
json 1 "$(err invalid-map 1) and 'is stale' in j['error']['message']" -- "$sp" plan --map "$tmp/motion/map.json" \
  --mission "$mission" --no-motion --route-index "$tmp/plus.bin" --json

# The map's coordinate reference system (--crs), and export-geojson (docs/cli.md)
json 0 "j['crs'] is None" -- "$sp" info --map "$ais" --json
json 2 "$(err usage 2) and j['error']['message'].startswith('--crs')" -- \
  "$sp" info --map "$ais" --crs EPSG:x25 --json
json 0 "j['crs'] == 'EPSG:25832'" -- "$sp" convert --map "$ais" --crs epsg:25832 -o "$tmp/utm.json" --json
json 0 "j['crs'] == 'EPSG:25832'" -- "$sp" info --map "$tmp/utm.json" --json
json 2 "$(err usage 2) and 'names its own CRS' in j['error']['message']" -- \
  "$sp" info --map "$tmp/utm.json" --crs EPSG:31467 --json
json 0 "j['valid'] is True" -- "$sp" validate --map "$ais" --crs EPSG:25832 --json
json 2 "$(err usage 2) and 'names its own CRS' in j['error']['message']" -- \
  "$sp" validate --map "$tmp/utm.json" --crs EPSG:31467 --json
json 0 "len(j['steps']) == 14" -- \
  "$sp" plan --map "$tmp/utm.json" --crs EPSG:25832 --mission "$mission" --json -q
json 2 "$(err usage 2) and 'names its own CRS' in j['error']['message']" -- \
  "$sp" plan --map "$tmp/utm.json" --crs EPSG:31467 --mission "$mission" --json
if "$sp" --help | grep -q export-geojson; then
  json 2 "$(err usage 2) and 'no coordinate reference system' in j['error']['message']" -- \
    "$sp" export-geojson --map "$ais" -o "$tmp/ais.geojson" --json
  json 0 "j['crs'] == 'EPSG:25832' and j['wrote'].endswith('ais.geojson') and j['plan_steps'] > 0 and j['driveability'] is True and j['nav2'].endswith('nav2.geojson')" -- \
    "$sp" export-geojson --map "$ais" --assume-crs EPSG:25832 --mission "$mission" --plan-route \
    --profile makro-plus -o "$tmp/ais.geojson" --nav2 "$tmp/nav2.geojson" --json
  json 0 "j['plan_steps'] == 14" -- "$sp" export-geojson --map "$tmp/utm.json" --mission "$mission" \
    --plan "$plans/paper-corrected.plan" -o "$tmp/ais.geojson" --json
  json 2 "$(err usage 2)" -- "$sp" export-geojson --map "$ais" --json
fi

# --gis-fields FILE (docs/cli.md) on every command that reads a map: a missing file is an I/O error
# naming it before any map is read; one given for a map that is no GIS source is a usage error (the
# GIS sources themselves: tests/gis/gis_round_trip.sh).
json 3 "$(err io 3) and j['error']['message'] == '--gis-fields $tmp/no-fields.json: no such file'" -- \
  "$sp" plan --map "$ais" --mission "$mission" --gis-fields "$tmp/no-fields.json" --json
echo '{}' > "$tmp/fields.json"
if "$sp" --help | grep -q export-geojson; then
  json 2 "$(err usage 2) and 'is not a GIS source' in j['error']['message']" -- \
    "$sp" validate --map "$ais" --gis-fields "$tmp/fields.json" --json
else
  json 1 "$(err unsupported-format 1)" -- "$sp" validate --map "$ais" --gis-fields "$tmp/fields.json" --json
fi

# A command-line error that CLI11 finds (an unknown option) is an error object too.
json 2 "$(err usage 2)" -- "$sp" validate --map "$ais" --frobnicate --json

report=$(check_all)
# The last line is the number of checks that passed; any line before it names a failure.
evaluated=$(tail -n 1 <<<"$report")
if [[ "$evaluated" =~ ^[0-9]+$ ]]; then
  head -n -1 <<<"$report"
  passed=$((passed + evaluated))
  failures=$((failures + checks - evaluated))
else
  echo "FAIL: the JSON checks did not run:"; echo "$report"; failures=$((failures + checks))
fi
echo "json: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
