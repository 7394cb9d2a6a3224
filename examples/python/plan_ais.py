#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Plans the MAKRO paper's mission on the AIS test environment, then replans after a blockage.

Usage: plan_ais.py [DATASET_DIR]   (default: the repository's datasets/ais-testbed, else the
Debian package's /usr/share/sewerplan/datasets/ais-testbed)
"""
import pathlib
import sys

import sewerplan


def dataset_dir():
    if len(sys.argv) > 1:
        return pathlib.Path(sys.argv[1])
    here = pathlib.Path(__file__).resolve().parents[2] / "datasets" / "ais-testbed"
    return here if here.exists() else pathlib.Path("/usr/share/sewerplan/datasets/ais-testbed")


def main():
    data = dataset_dir()
    try:
        sewer = sewerplan.read_map(str(data / "map.json"))
        mission = sewerplan.read_mission(sewer, str(data / "missions" / "paper.json"))
        outcome = sewerplan.plan(mission, time_limit_s=1.0)
    except sewerplan.Error as error:
        for d in error.diagnostics:
            print(d, file=sys.stderr)
        print(f"{error.code}: {error.message}", file=sys.stderr)
        return 1
    print(outcome.plan.text, end="")
    print(f"{len(outcome.plan)} steps, {outcome.cost_s:.1f} s, {outcome.energy_wh:.1f} Wh "
          f"({outcome.algorithm}{', optimal' if outcome.optimal else ''})")

    # The robot meets a blockage in P4 that its recovery cannot clear.
    replanner = sewerplan.Replanner(mission)
    replanner.plan()
    response = replanner.report_failure(sewerplan.FailureKind.BLOCKAGE, pipe="P4", offset_m=2.0)
    print(f"after '{response.reason}': {response.decision.label}, ends at {response.end}")
    for dropped in response.newly_dropped:
        print(f"dropped '{dropped.task}': {dropped.reason}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
