#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Compares the plans of two sewerplan builds on the planner's instance sets (issue 33).

    python3 scripts/portfolio-compare.py OLD_SEWERPLAN NEW_SEWERPLAN [WORKDIR]

The instances: generated meshed networks (`sewerplan generate`) of 1,000, 10,000 and 100,000
manholes with 5, 10, 15, 18, 20 and 50 tasks, uniform and clustered, seeds 1 and 2; and the real
networks of datasets/ with their missions (the AIS test environment's paper mission, the
condition missions on the swmmio state-plane model and the battery trap). Each is planned once
by each build with the default options (`plan --json`, with `--select-goals` on the generated
networks and the battery trap); a row per instance gives both plans'
cost_s, the tasks each left out, the planning time (compile + search, as the plan reports it)
and the algorithm, and a last row the sums. Deterministic plans; the times are the machine's.
"""
import json
import os
import subprocess
import sys

old, new = sys.argv[1], sys.argv[2]
work = sys.argv[3] if len(sys.argv) > 3 else "/tmp/sewerplan-portfolio"
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
os.makedirs(work, exist_ok=True)

instances = []
for n in (1000, 10000, 100000):
    for tasks in (5, 10, 15, 18, 20, 50):
        for spread in ("uniform", "clustered"):
            for seed in (1, 2):
                name = f"meshed-{n}-{tasks}-{spread}-{seed}"
                m, mi = f"{work}/{name}.sewer", f"{work}/{name}.mission.json"
                if not os.path.exists(mi):
                    subprocess.run([old, "generate", "-n", str(n), "-s", str(seed), "-t", "meshed",
                                    "-o", m, "--mission-tasks", str(tasks), "--mission-spread",
                                    spread, "--mission-out", mi], check=True,
                                   stdout=subprocess.DEVNULL)
                instances.append((name, m, mi, ["--select-goals"]))
instances.append(("ais-paper", f"{root}/datasets/ais-testbed/map.json",
                  f"{root}/datasets/ais-testbed/missions/paper.json", []))
instances.append(("swmm-state-plane", f"{root}/datasets/swmm/swmmio-state-plane.inp",
                  f"{root}/datasets/condition/swmm-state-plane/mission.json", []))
instances.append(("battery-trap", f"{root}/datasets/condition/battery-trap/map.json",
                  f"{root}/datasets/condition/battery-trap/mission.json", ["--select-goals"]))


def plan(binary, m, mi, extra):
    r = subprocess.run([binary, "plan", "--map", m, "--mission", mi, "--json", "-q"] + extra,
                       capture_output=True, text=True)
    try:
        j = json.loads(r.stdout)
    except json.JSONDecodeError:
        return None
    if "cost_s" not in j:
        return None
    s = j["statistics"]
    return (j["cost_s"], len(j.get("dropped", [])),
            s["compile"]["time_s"] + s["search"]["time_s"], j.get("algorithm", ""))


print(f"{'instance':34} {'old_cost':>10} {'new_cost':>10} {'drop':>5} {'old_ms':>8} {'new_ms':>8}  new algorithm")
tot = [0.0, 0.0, 0.0, 0.0]
better = worse = 0
for name, m, mi, extra in instances:
    a, b = plan(old, m, mi, extra), plan(new, m, mi, extra)
    if a is None or b is None:
        print(f"{name:34} {'no plan' if a is None else a[0]:>10} {'no plan' if b is None else b[0]:>10}")
        continue
    tot[0] += a[0]
    tot[1] += b[0]
    tot[2] += a[2]
    tot[3] += b[2]
    if (b[1], b[0]) < (a[1], a[0] - 1e-6):
        better += 1
    elif (b[1], b[0]) > (a[1], a[0] + 1e-6):
        worse += 1
    print(f"{name:34} {a[0]:10.1f} {b[0]:10.1f} {a[1]:>2}/{b[1]:<2} {a[2]*1e3:8.1f} {b[2]*1e3:8.1f}  {b[3]}")
print(f"{'sum':34} {tot[0]:10.1f} {tot[1]:10.1f} {'':5} {tot[2]*1e3:8.1f} {tot[3]*1e3:8.1f}  "
      f"{better} better, {worse} worse")
