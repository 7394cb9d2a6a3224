#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The chance-constraint table of docs/planning.md ("A bound on the chance of being stranded",
# issue 34): one campaign per bound P on one network with its condition data, obstacles drawn from
# the condition data only, and per P the tasks done (ours, the risk-aware execution, the oracle), the
# share of missed exits with its 95 % Wilson interval, and the mean stranding risk the first plans
# computed (summary.json: ours / risk_aware .tasks_mean, .missed_exit_share,
# .missed_exit_share_95, .strand_risk_mean).
#
#   [NETWORK=battery-trap|swmm-state-plane] scripts/strand-risk-table.sh BINARY [RUNS] [P ...]
#
# BINARY: a built sewerplan (build/release/bin/sewerplan); RUNS: runs per P (default 2000, the
# issue's acceptance); P: the bounds (default 0 0.01 0.05 0.2 1). NETWORK: battery-trap (the
# default: the generated 400-manhole network with findings in its map) or swmm-state-plane (the
# real SWMM model with its synthetic Zustandsdaten joined by --condition; datasets/condition/
# README.md). One battery-trap run takes about a second on one core (docs/planning.md): 2,000 runs
# x 5 bounds is hours; JOBS=N runs N at once. Output: one Markdown row per P on standard output;
# each campaign's directory under ${OUT:-strand-risk-out}/P.
set -euo pipefail
bin=${1:?usage: strand-risk-table.sh BINARY [RUNS] [P ...]}
runs=${2:-2000}
shift $(( $# >= 2 ? 2 : 1 ))
bounds=("$@")
[ ${#bounds[@]} -gt 0 ] || bounds=(0 0.01 0.05 0.2 1)
here=$(cd "$(dirname "$0")/.." && pwd)
network=${NETWORK:-battery-trap}
case $network in
  battery-trap)
    world=(--map "$here/datasets/condition/battery-trap/map.json"
      --mission "$here/datasets/condition/battery-trap/mission.json") ;;
  swmm-state-plane)
    world=(--map "$here/datasets/swmm/swmmio-state-plane.inp"
      --condition "$here/datasets/condition/swmm-state-plane/zustand.xml"
      --mission "$here/datasets/condition/swmm-state-plane/mission.json") ;;
  *) echo "unknown NETWORK $network (battery-trap, swmm-state-plane)" >&2; exit 2 ;;
esac
out=${OUT:-strand-risk-out}
jobs=${JOBS:-1}
mkdir -p "$out"
echo "| P | runs | ours: tasks / oracle | ours: missed exits [95 %] | ours: computed risk, mean | risk-aware: tasks | risk-aware: missed exits [95 %] | risk-aware: computed risk, mean |"
echo "|---|---|---|---|---|---|---|---|"
for p in "${bounds[@]}"; do
  dir="$out/$p"
  rm -rf "$dir"
  "$bin" campaign "${world[@]}" --runs "$runs" --seed 1 \
    --risk expected --faults-from-condition \
    --fault-rates obstacles=0,danger=0,passages=0,malfunctions=0 \
    --max-strand-risk "$p" --jobs "$jobs" --out "$dir" >/dev/null || {
    # Exit 6: the campaign ran but is not clean (missed exits): what this table measures.
    code=$?
    [ "$code" -eq 6 ] || exit "$code"
  }
  python3 - "$dir/summary.json" "$p" "$runs" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
def f(x, d=4):
    return "-" if x is None else f"{x:.{d}f}"
def row(k):
    p = s[k]
    lo, hi = p["missed_exit_share_95"]
    return (f"{f(p['tasks_mean'], 2)}",
            f"{p['missed_exits']} of {p['could_reach_exit']}: {f(p['missed_exit_share'])} [{f(lo)}, {f(hi)}]",
            f(p["strand_risk_mean"]))
o, r = row("ours"), row("risk_aware")
print(f"| {sys.argv[2]} | {sys.argv[3]} | {o[0]} / {f(s['oracle_tasks_mean'], 2)} | {o[1]} | {o[2]} | {r[0]} | {r[1]} | {r[2]} |")
PY
done
