#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""What `sewerplan plan` blames when it finds no plan on the shipped SWMM networks (issue 30).

For each .inp in datasets/swmm, each built-in profile and two batteries (the profile's, and
100 kWh), one mission per manhole: lowered into that manhole, inspect one pipe (chosen by a fixed
stride through the map's pipes), come out at any manhole ("exits": "all"). Each "no plan" answer
is sorted by what it names as the cause; the table is printed as Markdown.

  python3 scripts/swmm-no-plan-causes.py build/release/bin/sewerplan [--select-goals]
"""
import collections
import json
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent


def cause(message):
    if "in the way:" in message:
        return "limit or closure named"
    if "does not connect" in message:
        return "network not connected"
    if "starts in pipe" in message:
        return "start pipe undrivable"
    if "needs more than" in message or "needs at least" in message or "within the battery" in message \
            or "every route to one needs more" in message:
        return "battery"
    if "Wh left" in message and "within" in message:
        return "battery and limits (unsure)"
    if "m, outside" in message:
        return "the task's pipe: its diameter named"
    if "'s limits" in message:
        return "limits, none named"
    return "other: " + message.strip().splitlines()[-1][:80]


def main():
    binary = sys.argv[1]
    extra = sys.argv[2:]
    rows = collections.OrderedDict()
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        for inp in sorted((ROOT / "datasets" / "swmm").glob("*.inp")):
            converted = tmp / (inp.stem + ".json")
            subprocess.run([binary, "convert", "--map", str(inp), "-o", str(converted)],
                           check=True, capture_output=True)
            net = json.loads(converted.read_text())
            pipes = [p["name"] for p in net["pipes"]]
            for profile in ("makro-1.1", "makro-plus"):
                for battery in (None, 100000):
                    counts = collections.Counter()
                    for i, manhole in enumerate(net["manholes"]):
                        prof = profile if battery is None else {"base": profile, "battery_wh": battery}
                        mission = {"format": "sewerplan-mission", "version": 1, "profile": prof,
                                   "start": {"manhole": manhole["name"]},
                                   "tasks": [{"type": "inspect_pipe",
                                              "pipe": pipes[(i * 7) % len(pipes)]}],
                                   "exits": "all"}
                        path = tmp / "mission.json"
                        path.write_text(json.dumps(mission))
                        run = subprocess.run([binary, "plan", "-q", "--map", str(inp), "--mission",
                                              str(path), "--time-limit", "10"] + extra,
                                             capture_output=True, text=True)
                        if run.returncode == 0:
                            counts["plan"] += 1
                        elif run.returncode == 4:
                            counts[cause(run.stderr)] += 1
                        else:
                            counts["exit %d" % run.returncode] += 1
                    rows[(inp.name, profile, "100 kWh" if battery else "profile's")] = counts
    kinds = sorted({k for c in rows.values() for k in c})
    print("| network | profile | battery | " + " | ".join(kinds) + " |")
    print("|---|---|---|" + "--:|" * len(kinds))
    for (net, profile, battery), counts in rows.items():
        print(f"| {net} | {profile} | {battery} | " + " | ".join(str(counts[k]) for k in kinds) + " |")


if __name__ == "__main__":
    main()
