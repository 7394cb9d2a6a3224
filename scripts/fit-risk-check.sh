#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# How close `sewerplan fit-risk` comes to known probabilities (issue 34; docs/planning.md,
# "Fitting the table"): a "true" risk table (the built-in one with roots x 0.5, attached deposits
# x 3, settled deposits x 2, obstacles x 1.5, breaks 0.5 -> 0.2) draws the campaign's faults
# (--faults-from-condition, no random faults); fit-risk fits the table from the campaign's
# outcomes with the built-in table as its prior; per rule: the observations, the true, prior and
# fitted probability, the true and fitted mean probability of the findings observed with the
# fitted 90 % interval, and whether the truth lies in it. (The true mean is what the true table
# gives those findings: a fit with the true table as prior reports it as `mean_prior`.)
#
#   scripts/fit-risk-check.sh BINARY [RUNS] [NETWORK]
#
# BINARY: a built sewerplan (build/release/bin/sewerplan); RUNS: default 300; NETWORK:
# swmm-state-plane (default, about 0.05 s a run) or battery-trap (about 1 s a run).
# Output: a Markdown table on standard output; the files under ${OUT:-fit-risk-out}.
set -euo pipefail
bin=${1:?usage: fit-risk-check.sh BINARY [RUNS] [NETWORK]}
runs=${2:-300}
network=${3:-swmm-state-plane}
here=$(cd "$(dirname "$0")/.." && pwd)
out=${OUT:-fit-risk-out}
mkdir -p "$out"
case $network in
  swmm-state-plane)
    world=(--map "$here/datasets/swmm/swmmio-state-plane.inp"
      --condition "$here/datasets/condition/swmm-state-plane/zustand.xml"
      --mission "$here/datasets/condition/swmm-state-plane/mission.json") ;;
  battery-trap)
    world=(--map "$here/datasets/condition/battery-trap/map.json"
      --mission "$here/datasets/condition/battery-trap/mission.json") ;;
  *) echo "unknown network $network (swmm-state-plane, battery-trap)" >&2; exit 2 ;;
esac
python3 - "$here/datasets/condition/default-risk-table.json" "$out/true.json" <<'PY'
import json, sys
t = json.load(open(sys.argv[1]))
scale = {'BBA': 0.5, 'BBE': 1.5, 'BBB': 3.0, 'BBC': 2.0}
for r in t['rules']:
    if r['code'] == 'BAC' and r.get('characterisation') == 'B':
        r['probability'] = 0.2
    if r['code'] in scale:
        r['probability'] = round(r['probability'] * scale[r['code']], 6)
        r['probability_per_percent'] = round(r['probability_per_percent'] * scale[r['code']], 6)
json.dump(t, open(sys.argv[2], 'w'), indent=2)
PY
rm -rf "$out/campaign"
# Exit code 6 (not clean: missed exits) is a finding of the campaign, not a failure here.
"$bin" campaign "${world[@]}" --risk-table "$out/true.json" --runs "$runs" --seed 1 \
  --faults-from-condition --fault-rates obstacles=0,danger=0,passages=0,malfunctions=0 \
  --jobs "${JOBS:-1}" -q -o "$out/campaign" >/dev/null || [ $? -eq 6 ]
"$bin" fit-risk --campaign "$out/campaign" -o "$out/fitted.json" >&2
"$bin" fit-risk --campaign "$out/campaign" --risk-table "$out/true.json" \
  -o "$out/truth.json" >/dev/null
python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
def rules(name):
    return {(r['code'], r.get('characterisation', '')): r
            for r in json.load(open(f'{out}/{name}'))['rules'] if r['effect'] == 'blockage'}
fit, true, truth = rules('fitted.json'), rules('true.json'), rules('truth.json')
print('| rule | observations (blocked) | prior p | true p | fitted p | true mean of the findings seen | fitted mean [90 %] | truth inside |')
print('|---|---|---|---|---|---|---|---|')
for key, r in fit.items():
    f = r['fit']
    name = key[0] + ('/' + key[1] if key[1] else '') + ' ' + r['meaning']
    if f['observations'] == 0:
        print(f"| {name} | 0 | {f['prior_probability']:.3f} | {true[key]['probability']:.3f} | "
              f"{r['probability']:.3f} (prior) | - | - | - |")
        continue
    m = truth[key]['fit']['mean_prior']
    inside = 'yes' if f['mean_low'] <= m <= f['mean_high'] else 'no'
    print(f"| {name} | {f['observations']} ({f['blockages']}) | {f['prior_probability']:.3f} | "
          f"{true[key]['probability']:.3f} | {r['probability']:.3f} | {m:.3f} | "
          f"{f['mean']:.3f} [{f['mean_low']:.3f}, {f['mean_high']:.3f}] | {inside} |")
PY
