# SPDX-License-Identifier: MIT
# Planning, checking and the Replanner from Python, and the GIL released while planning.
import threading

import pytest

import sewerplan
from conftest import AIS


def test_plans_the_paper_mission(paper):
    outcome = sewerplan.plan(paper, time_limit_s=5.0)
    assert outcome.plan.text == (AIS / "plans" / "paper-corrected.plan").read_text()
    assert len(outcome.plan) == 14
    assert outcome.cost_s == pytest.approx(585.377)
    assert outcome.energy_wh == pytest.approx(19.5126, abs=1e-3)
    assert outcome.optimal
    assert outcome.dropped == []
    assert outcome.statistics.expanded > 0
    first = outcome.plan.steps[0]
    assert (first.kind, first.pipe, first.manhole) == ("drive_pipe_to_manhole", "P12", "M2")
    assert [s.task for s in outcome.plan.steps if s.task] == ["sample", "inspect"]
    actions = outcome.plan.actions
    assert len(actions) == 14
    assert actions[0].kind == "drive_to_manhole"
    assert sum(a.duration_s for a in actions) == pytest.approx(outcome.cost_s, abs=0.01)


def test_each_algorithm_gives_a_valid_plan(paper):
    for algorithm in ["ehc", "gbfs", "wastar", "astar", "exact"]:
        outcome = sewerplan.plan(paper, algorithm=algorithm)
        assert sewerplan.check(outcome.plan).valid, algorithm
    with pytest.raises(sewerplan.Error) as error:
        sewerplan.plan(paper, algorithm="magic")
    assert error.value.code == "invalid-argument"


def impossible(ais_map):
    # P4 is closed: its inspection cannot be done.
    return sewerplan.mission(ais_map, start="P12", exits=["M1"], closed_pipes=["P4"],
                             tasks=[sewerplan.take_water_sample("W1", name="sample"),
                                    sewerplan.inspect_pipe("P4", name="inspect")])


def test_no_plan_raises_with_the_reasons(ais_map):
    with pytest.raises(sewerplan.Error) as error:
        sewerplan.plan(impossible(ais_map))
    assert error.value.code == "no-plan"
    assert "P4" in error.value.message


def test_goal_selection_drops_tasks_with_reasons(ais_map):
    outcome = sewerplan.plan(impossible(ais_map), select_goals=True)
    assert [d.task for d in outcome.dropped] == ["inspect"]
    assert "P4" in outcome.dropped[0].reason
    report = sewerplan.check(outcome.plan)  # every step runs; the dropped task is not done
    assert report.failed_step is None
    assert "inspect" in report.error


def test_check_finds_the_broken_step(paper):
    text = (AIS / "plans" / "paper-corrected.plan").read_text().splitlines()
    broken = "\n".join(text[1:]) + "\n"  # the first drive left out
    report = sewerplan.check(sewerplan.parse_plan(paper, broken, "broken.plan"))
    assert not report.valid
    assert report.failed_step == 0
    assert report.error.startswith("step 1 (DRIVE_MANHOLE")  # numbered from 1
    good = sewerplan.check(sewerplan.parse_plan(paper, "\n".join(text) + "\n"))
    assert good.valid and good.total_cost_s == pytest.approx(585.4, abs=0.05)


def test_a_bad_plan_line_names_file_and_line(paper):
    with pytest.raises(sewerplan.Error) as error:
        sewerplan.parse_plan(paper, "DRIVE_PIPE_TO_MANHOLE P12 M2\nFLY_HOME\n", "x.plan")
    assert error.value.code == "parse"
    assert [(d.file, d.line) for d in error.value.diagnostics] == [("x.plan", 2)]


def test_replanner_decisions(paper):
    replanner = sewerplan.Replanner(paper)
    first = replanner.plan()
    assert first.decision == sewerplan.Decision.FOLLOW_PLAN
    assert first.decision.label == "follow-plan"
    assert first.goals == ["sample", "inspect", "end"]
    assert first.has_plan and not first.calls_beacon
    replanner.update(manhole="M2", energy_used_wh=0.3)
    blocked = replanner.report_failure(sewerplan.FailureKind.BLOCKAGE, pipe="P4", offset_m=2.0)
    assert blocked.decision == sewerplan.Decision.DEGRADED
    assert [d.task for d in blocked.newly_dropped] == ["inspect"]
    assert "blockage in P4" in blocked.reason
    assert sewerplan.check(blocked.plan).failed_step is None
    assert [d.task for d in replanner.dropped] == ["inspect"]
    bad = replanner.report_failure(sewerplan.FailureKind.BLOCKAGE, pipe="P4", offset_m=-5.0)
    assert bad.decision == sewerplan.Decision.INVALID_REPORT
    stuck = replanner.report_failure(sewerplan.FailureKind.STUCK)
    assert stuck.decision == sewerplan.Decision.STUCK and stuck.calls_beacon
    with pytest.raises(sewerplan.Error):
        replanner.update(manhole="M99")


def test_planning_releases_the_gil():
    # A search that would run for minutes: A* with h_max over 40 tasks on a generated network. It
    # stops only when the other thread cancels it, which that thread can do only while plan()
    # runs without the GIL (held, the helper could never set the event nor cancel: the search
    # would stop at its time limit with 'search-limit' instead).
    network = sewerplan.generate_network(manholes=3000, seed=3)
    mission = sewerplan.generate_mission(network, tasks=40, seed=3)
    token = sewerplan.CancelToken()
    other_thread_ran = threading.Event()

    def helper():
        token.wait_entered()  # plan() is running
        other_thread_ran.set()
        token.cancel()

    thread = threading.Thread(target=helper)
    thread.start()
    with pytest.raises(sewerplan.Error) as error:
        sewerplan.plan(mission, algorithm="astar", time_limit_s=120, cancel=token)
    thread.join()
    assert other_thread_ran.is_set()
    assert error.value.code == "cancelled"
