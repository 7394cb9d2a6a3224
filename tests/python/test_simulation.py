# SPDX-License-Identifier: MIT
# Simulated missions with faults (events as objects) and a small campaign from Python.
import json

import sewerplan
from conftest import AIS


def test_simulates_a_blocked_pipe(ais_map, paper):
    faults = sewerplan.read_faults(ais_map, str(AIS / "faults" / "blocked-p5.json"))
    assert faults.obstacles >= 1
    run = sewerplan.simulate(paper, faults)
    report = run.report
    assert report.outcome == "ended"
    assert report.replans >= 1
    events = run.events
    assert events[0].type == "plan" and isinstance(events[0].what, sewerplan.PlanEvent)
    assert events[-1].type == "mission_end"
    assert isinstance(events[-1].what, sewerplan.MissionEndEvent)
    assert events[-1].what.tasks_done == report.tasks_done
    failures = [e.what for e in events if e.type == "failure"]
    assert failures and failures[0].kind == sewerplan.FailureKind.BLOCKAGE
    assert failures[0].pipe == "P5"
    assert [e.t_s for e in events] == sorted(e.t_s for e in events)
    assert json.loads(events[0].to_json())["type"] == "plan"


def unmeasured(events):
    """The events without the planning times, which are measured."""
    lines = [json.loads(e.to_json()) for e in events]
    for line in lines:
        line.pop("planning_ms", None)
    return lines


def test_simulation_is_deterministic(paper):
    faults = sewerplan.random_faults(paper, seed=7, obstacles_per_km=40)
    first = sewerplan.simulate(paper, faults)
    second = sewerplan.simulate(paper, faults)
    assert unmeasured(first.events) == unmeasured(second.events)


def test_without_faults_every_task_is_done(paper):
    report = sewerplan.simulate(paper).report
    assert report.outcome == "ended"
    assert report.tasks_done == ["sample", "inspect", "end"]
    assert report.end == "pipe P9 (final task 'end')"
    assert report.decision == sewerplan.Decision.FOLLOW_PLAN
    assert report.battery_reserve_kept


def test_a_small_campaign(paper):
    campaign = sewerplan.run_campaign(paper, runs=3, seed=1, jobs=2)
    assert [r.index for r in campaign.records] == [0, 1, 2]
    assert all(r.status == "ok" for r in campaign.records)
    assert all(r.ours.tasks <= r.oracle_tasks for r in campaign.records if r.oracle_tasks >= 0)
    summary = campaign.summary
    assert summary.runs == 3 and summary.completed == 3
    assert summary.clean
    assert json.loads(summary.to_json())["runs"] == 3
    again = sewerplan.run_campaign(paper, runs=3, seed=1, guard=False)
    assert [r.ours.tasks for r in again.records] == [r.ours.tasks for r in campaign.records]
