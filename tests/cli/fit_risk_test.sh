#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# sewerplan fit-risk (issue 34; docs/cli.md, docs/planning.md "Fitting the table"): a short
# campaign with condition-drawn faults on the SWMM state-plane network records what each robot met
# at the hazards; fit-risk fits the risk table from it (and from a simulate --log), deterministic;
# plan --risk-table uses the fitted table (each hazard's probability the prior's scaled by its
# rule's posterior mean over prior mean); bad input names the file and line.
# Usage: fit_risk_test.sh PATH_TO_SEWERPLAN SOURCE_DIR
set -uo pipefail
sp=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
source "$(dirname "${BASH_SOURCE[0]}")/expect.sh"
expect_timeout=60  # a hang fails

map=$src/datasets/swmm/swmmio-state-plane.inp
condition=$src/datasets/condition/swmm-state-plane/zustand.xml
mission=$src/datasets/condition/swmm-state-plane/mission.json
world=(--map "$map" --condition "$condition" --mission "$mission")

expect 0 "" -- "$sp" campaign "${world[@]}" --runs 4 --seed 1 --faults-from-condition \
  --fault-rates obstacles=0,danger=0,passages=0,malfunctions=0 --jobs 1 -q -o "$tmp/c"
check "the campaign records the hazards its robots met" grep -q '"hazards":\[{"pipe"' "$tmp/c/runs.jsonl"

# The fit: every observation of a run once, the rules nobody saw kept as the prior.
"$sp" fit-risk --campaign "$tmp/c" -o "$tmp/fit.json" >"$tmp/fit.txt" 2>&1
check "fit-risk succeeds" test $? -eq 0
for line in "^fitted $tmp/fit.json from [1-9][0-9]* observations in 4 missions \\(prior strength 2, 90 % intervals\\)" \
  "^  BBA +roots +[0-9]+ blocked of [1-9][0-9]*: probability 0.20 -> 0.[0-9]+ \\(the findings seen: .* interval " \
  "^  BBC +settled deposits +no observations: the prior, probability 0.10$"; do
  check "fit-risk prints /$line/" grep -qE -- "$line" "$tmp/fit.txt"
done
"$sp" fit-risk --campaign "$tmp/c" -o "$tmp/j.json" --json 2>/dev/null >"$tmp/summary.json"
check "the fit is deterministic" cmp -s "$tmp/fit.json" "$tmp/j.json"
check "the --json summary's counts add up to the observations" python3 -c "
import json, sys
j = json.load(open('$tmp/summary.json'))
fitted = sum(r['observations'] for r in j['rules'])
assert fitted + j['unfitted'] == j['observations'] > 0, j
assert all(r['mean_low'] <= r['mean'] <= r['mean_high'] for r in j['rules'])
"

# The planner uses the fitted table: each hazard's probability is the prior's scaled by its rule's
# posterior mean / prior mean (BBA roots, BBE obstacles: both observed in the campaign).
"$sp" plan "${world[@]}" --risk expected --select-goals --json 2>/dev/null >"$tmp/prior-plan.json"
"$sp" plan "${world[@]}" --risk expected --select-goals --risk-table "$tmp/fit.json" --json \
  2>/dev/null >"$tmp/fit-plan.json"
check "plan --risk-table FITTED weighs the fitted probabilities" python3 -c "
import json
table = {r['code']: r for r in json.load(open('$tmp/fit.json'))['rules'] if r.get('fit')}
prior = json.load(open('$tmp/prior-plan.json'))['risk']['hazards']
fitted = json.load(open('$tmp/fit-plan.json'))['risk']['hazards']
assert len(prior) == len(fitted) > 0
seen = 0
for a, b in zip(prior, fitted):
    assert (a['pipe'], a['offset_m'], a['reason']) == (b['pipe'], b['offset_m'], b['reason'])
    f = table[a['reason'].split()[0]]['fit']
    if f['observations'] == 0 or a['probability'] >= 1:
        continue
    scale = f['mean'] / f['mean_prior']
    assert abs(b['probability'] - min(1.0, a['probability'] * scale)) < 1e-9, (a, b, scale)
    seen += 1
assert seen > 0
"

# From a mission's event log: each hazard once, whatever the passes.
expect 0 "" -- "$sp" simulate "${world[@]}" --risk expected --random-faults 3 --log "$tmp/ev.jsonl"
hazards=$(grep '"hazard"' "$tmp/ev.jsonl" | python3 -c "
import json, sys
print(len({(e['pipe'], e['offset_m'], e['reason']) for e in map(json.loads, sys.stdin)}))")
expect 0 "from $hazards observations in 1 missions" -- "$sp" fit-risk --log "$tmp/ev.jsonl" \
  --map "$map" --condition "$condition" -o "$tmp/log.json"

# Bad input names what is wrong and where.
expect 2 "give at least one --campaign DIR or --log" -- "$sp" fit-risk -o "$tmp/x.json"
expect 2 "--log needs --map" -- "$sp" fit-risk --log "$tmp/ev.jsonl" -o "$tmp/x.json"
expect 2 "--level must be between 0 and 1" -- "$sp" fit-risk --campaign "$tmp/c" --level 1 -o "$tmp/x.json"
cp -r "$tmp/c" "$tmp/other"
sed -i 's/"map_fingerprint": *"[0-9a-f]*"/"map_fingerprint": "0123456789abcdef"/' "$tmp/other/campaign.json"
expect 1 "other/campaign.json: the map .* is not the campaign's" -- "$sp" fit-risk \
  --campaign "$tmp/other" -o "$tmp/x.json"
cp -r "$tmp/c" "$tmp/rel"
sed -i 's|"map": "[^"]*"|"map": "nowhere/map.inp"|' "$tmp/rel/campaign.json"
expect 3 "rel/campaign.json: cannot read nowhere/map.inp.*give --map and --condition" -- "$sp" \
  fit-risk --campaign "$tmp/rel" -o "$tmp/x.json"
cp -r "$tmp/c" "$tmp/moved"
sed -i '2s/"offset_m":\([0-9.]*\),"reason"/"offset_m":0.125,"reason"/' "$tmp/moved/runs.jsonl"
expect 1 "runs.jsonl:2: the hazard in pipe .* at 0.125 m .* is no finding of the condition data" \
  -- "$sp" fit-risk --campaign "$tmp/moved" -o "$tmp/x.json"
python3 -c "
import json, sys
out = []
for line in open('$tmp/ev.jsonl'):
    e = json.loads(line)
    if e.get('type') == 'hazard': e['pipe'] = 'NOPE'
    out.append(json.dumps(e))
open('$tmp/bad.jsonl', 'w').write('\n'.join(out) + '\n')"
expect 1 "bad.jsonl:[0-9]+: hazard in pipe 'NOPE'" -- "$sp" fit-risk --log "$tmp/bad.jsonl" \
  --map "$map" --condition "$condition" -o "$tmp/x.json"
echo '{"format": "sewerplan-risk-table", "version": 1, "rules": [{"code": "BBA", "effect": "blocked"}]}' >"$tmp/prior.json"
expect 1 "prior.json:\\\$.rules\[0\].effect" -- "$sp" fit-risk --campaign "$tmp/c" \
  --risk-table "$tmp/prior.json" -o "$tmp/x.json"
expect 3 "$tmp/no/such/dir" -- "$sp" fit-risk --campaign "$tmp/c" -o "$tmp/no/such/dir/x.json"

echo "fit_risk_test: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
