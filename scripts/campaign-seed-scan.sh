#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs one campaign per seed over a range of seeds and lists every run where ours missed an exit
# the oracle reached, with its end; then the totals. A campaign of the AIS testbed in the
# realistic world takes about a second, so a scan of many seeds shows the classes of failure that
# the few seeds a change was looked at on do not (docs/campaign.md, "Seeds never looked at").
#
#   scripts/campaign-seed-scan.sh build/release/bin/sewerplan datasets/ais-testbed/map.json \
#       datasets/ais-testbed/missions/paper.json 200 5 80 out/scan-ais [realistic]
#
# Each seed's campaign is written to OUT/seed-N (kept: a second scan with the same OUT reuses it;
# remove OUT to run again). Replay a listed run with `sewerplan campaign ... --seed N --only RUN
# --log-out FILE`. Exit 0 when every campaign is clean, 6 otherwise, 2 on bad arguments.
set -euo pipefail

if [[ $# -lt 7 || $# -gt 8 ]]; then
  echo "usage: $0 SEWERPLAN MAP MISSION RUNS FIRST_SEED LAST_SEED OUT_DIR [WORLD_ERRORS]" >&2
  exit 2
fi
sewerplan=$1 map=$2 mission=$3 runs=$4 first=$5 last=$6 out=$7 world=${8:-realistic}
for n in "$runs" "$first" "$last"; do
  [[ $n =~ ^[0-9]+$ ]] || { echo "$0: '$n' is not a whole number" >&2; exit 2; }
done
[[ -x $sewerplan ]] || { echo "$0: $sewerplan is not an executable" >&2; exit 2; }
mkdir -p "$out"

for ((seed = first; seed <= last; ++seed)); do
  dir=$out/seed-$seed
  [[ -f $dir/summary.json ]] && continue
  # Exit 6 is a campaign that is not clean: what this scan looks for, not an error.
  status=0
  "$sewerplan" campaign --map "$map" --mission "$mission" --runs "$runs" --seed "$seed" \
    --world-errors "$world" --jobs 1 --quiet -o "$dir" > /dev/null || status=$?
  if [[ $status -ne 0 && $status -ne 6 ]]; then
    echo "$0: the campaign of seed $seed failed (exit $status)" >&2
    exit "$status"
  fi
done

python3 - "$out" "$first" "$last" <<'EOF'
import json
import sys

out, first, last = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
campaigns = clean = runs = missed = 0
for seed in range(first, last + 1):
    d = f"{out}/seed-{seed}"
    with open(f"{d}/summary.json") as f:
        summary = json.load(f)
    campaigns += 1
    clean += bool(summary["clean"])
    with open(f"{d}/runs.jsonl") as f:
        for line in f:
            r = json.loads(line)
            runs += 1
            ours = r["ours"]
            if r["could_reach_exit"] and ours["outcome"] not in ("exit", "end_point"):
                missed += 1
                print(f"seed {seed} run {r['run']}: {ours['outcome']} "
                      f"({ours['beacon_cause']}): {ours['end'][:200]}")
print(f"{campaigns} campaigns, {clean} clean; {runs} runs, {missed} missed an exit the oracle reached")
sys.exit(0 if clean == campaigns else 6)
EOF
