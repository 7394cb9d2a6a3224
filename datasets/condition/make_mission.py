#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes a seeded mission on a real network for the risk campaigns of docs/campaign.md.

    sewerplan convert --map NET -o net.json
    sewerplan info --map NET --profile makro-plus --start START --json > reach.json
    python3 make_mission.py net.json reach.json START SEED NAME > mission.json

The tasks are drawn (random.Random(SEED)) from the pipes makro-plus reaches from START: 8 of them,
the first 2 inspections, the other 6 water samples at 10 to 90 % of the pipe; the exits are START
and every dead end of that reachable part (manholes with one reachable pipe).
"""
import json
import random
import sys

net, reach, start, seed, name = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), sys.argv[5]
m = json.load(open(net, encoding="utf-8"))
pipes = sorted(json.load(open(reach, encoding="utf-8"))["driveability"]["reachable"]["pipes"])
by_name = {p["name"]: p for p in m["pipes"]}
degree = {}
for p in pipes:
    for end in (by_name[p]["from"], by_name[p]["to"]):
        degree[end] = degree.get(end, 0) + 1
rng = random.Random(seed)
tasks = []
for i, p in enumerate(rng.sample(pipes, min(8, len(pipes)))):
    if i < 2:
        tasks.append({"name": f"inspect-{p}", "type": "inspect_pipe", "pipe": p})
    else:
        offset = round(by_name[p]["length_m"] * (0.1 + 0.8 * rng.random()), 2)
        tasks.append({"name": f"sample-{p}", "type": "take_water_sample", "at": {"pipe": p, "offset_m": offset}})
exits = sorted({k for k, v in degree.items() if v == 1} | {start})
json.dump({"format": "sewerplan-mission", "version": 1, "name": name, "profile": "makro-plus",
           "start": {"manhole": start}, "tasks": tasks, "exits": exits, "battery_reserve": 0.2},
          sys.stdout, indent=2)
print()
