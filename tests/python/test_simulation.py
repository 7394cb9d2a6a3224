# SPDX-License-Identifier: MIT
# Simulated missions with faults (events as objects) and a small campaign from Python.
import json
import threading

import pytest

import sewerplan
from conftest import AIS


def test_simulates_a_blocked_pipe(ais_map, paper):
    faults = sewerplan.read_faults(ais_map, str(AIS / "faults" / "blocked-p5.json"))
    assert len(faults.obstacles) >= 1
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


def test_faults_are_objects(ais_map, paper):
    faults = sewerplan.read_faults(ais_map, str(AIS / "faults" / "blocked-p5.json"))
    obstacle = faults.obstacles[0]
    assert isinstance(obstacle, sewerplan.Obstacle)
    assert obstacle.pipe == "P5" and obstacle.kind in ("permanent", "transient")
    assert 0 <= obstacle.offset_m
    drawn = sewerplan.random_faults(paper, seed=3, obstacles_per_km=200)
    listed = json.loads(drawn.to_json())
    assert [o.pipe for o in drawn.obstacles] == [o["pipe"] for o in listed["obstacles"]]
    assert all(isinstance(d, sewerplan.DangerSpot) for d in drawn.danger_spots)
    for m in drawn.malfunctions:
        assert isinstance(m, sewerplan.Malfunction)
        assert (m.at_job is None) != (m.at_time_s is None)


def test_events_arrive_live_and_a_thread_halts_the_run(paper):
    """The callback sees each event as it happens, and halt() from another thread stops the run."""
    seen = []
    first_action = threading.Event()
    halted = threading.Event()

    def on_event(event):
        seen.append(event)
        if event.type == "action" and not first_action.is_set():
            first_action.set()
            # Hold the run here (the wait lets the GIL go) until the other thread has halted.
            assert halted.wait(timeout=60)

    halter = sewerplan.Halter()

    def halt_when_driving():
        assert first_action.wait(timeout=60)
        halter.halt()
        halted.set()

    thread = threading.Thread(target=halt_when_driving)
    thread.start()
    run = sewerplan.simulate(paper, on_event=on_event, halt=halter)
    thread.join()
    assert halter.requested
    assert run.report.outcome == "halted"
    assert run.report.tasks_done != ["sample", "inspect"]  # without the halt, both are done
    assert [e.type for e in seen] == [e.type for e in run.events]
    assert isinstance(seen[0].what, sewerplan.PlanEvent)
    assert seen[-1].type == "mission_end" and seen[-1].what.outcome == "halted"


def test_a_halter_used_before_the_run_halts_it_at_once(paper):
    halter = sewerplan.Halter()
    halter.halt()
    run = sewerplan.simulate(paper, halt=halter)
    assert run.report.outcome == "halted"
    assert not [e for e in run.events if e.type == "action"]


def test_an_exception_in_the_callback_halts_the_run_and_is_raised(paper):
    calls = []

    def on_event(event):
        calls.append(event.type)
        if event.type == "action":
            raise ValueError("enough")

    with pytest.raises(ValueError, match="enough"):
        sewerplan.simulate(paper, on_event=on_event)
    assert calls.count("action") == 1  # not called again after it raised


def with_findings(map_, findings):
    doc = json.loads(map_.to_json())
    doc["findings"] = findings
    return sewerplan.parse_map(json.dumps(doc), "with-findings.json")


def test_a_campaign_with_the_condition_options(ais_map):
    """risk and faults_from_condition, as sewerplan campaign --risk --faults-from-condition."""
    roots = [{"pipe": p["name"], "code": "BBA", "offset_m": p["length_m"] / 2}
             for p in ais_map.pipes]
    found = with_findings(ais_map, roots)
    assert found.finding_count == len(roots)
    mission = sewerplan.read_mission(found, str(AIS / "missions" / "paper.json"))
    campaign = sewerplan.run_campaign(mission, runs=2, seed=4, risk="expected",
                                      faults_from_condition=True, guard=False)
    assert all(r.status == "ok" for r in campaign.records)
    assert all(r.risk_aware is not None for r in campaign.records)
    summary = json.loads(campaign.summary.to_json())
    assert "risk_aware" in summary
    # What each run observed of the hazards, as its runs.jsonl line records it.
    observed = [h for r in campaign.records for h in r.risk_aware.hazards]
    assert observed
    for r in campaign.records:
        listed = json.loads(r.to_json())["risk_aware"].get("hazards", [])
        assert [(h.pipe, h.offset_m, h.reason, h.passes, h.blocked, h.probability)
                for h in r.risk_aware.hazards] == \
            [(h["pipe"], h["offset_m"], h["reason"], h["passes"], h["blocked"], h["probability"])
             for h in listed]
    for h in observed:
        assert isinstance(h, sewerplan.HazardBelief)
        assert ais_map.pipes[h.pipe]["length_m"] / 2 == pytest.approx(h.offset_m)
        assert h.reason.startswith("BBA")
        assert h.blocked == (h.probability == 1) and (h.blocked or h.passes >= 1)
    plain = sewerplan.run_campaign(mission, runs=2, seed=4, risk="ignore", guard=False)
    assert all(r.risk_aware is None for r in plain.records)
    assert all(not r.ours.hazards for r in plain.records)
    with pytest.raises(sewerplan.Error) as error:
        sewerplan.run_campaign(mission, runs=1, risk="sometimes")
    assert error.value.code == "invalid-argument"
    bare = sewerplan.read_mission(ais_map, str(AIS / "missions" / "paper.json"))
    with pytest.raises(sewerplan.Error, match="no possible blockage"):
        sewerplan.run_campaign(bare, runs=1, faults_from_condition=True)
