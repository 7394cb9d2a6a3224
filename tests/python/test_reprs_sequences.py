# SPDX-License-Identifier: MIT
# Reprs that say what a value is (never "<... object at 0x...>"), a Plan as a sequence of Steps,
# and a docstring on every public class, function and method.
import inspect
import re

import pytest

import sewerplan

DEFAULT_REPR = re.compile(r"object at 0x[0-9a-f]+")


def test_plan_is_a_sequence_of_steps(paper):
    plan = sewerplan.plan(paper).plan
    steps = plan.steps
    assert len(plan) == len(steps) == 14
    assert [s.text for s in plan] == [s.text for s in steps]
    assert plan[0].text == steps[0].text == "DRIVE_PIPE_TO_MANHOLE P12 M2"
    assert plan[-1].text == steps[-1].text and plan[-14].text == steps[0].text
    assert [s.text for s in plan[2:5]] == [s.text for s in steps[2:5]]
    for window in (slice(None, None, -3), slice(10, 100), slice(-3, None), slice(5, 2),
                   slice(-100, 3, 2)):
        assert [s.text for s in plan[window]] == [s.text for s in steps[window]], window
    with pytest.raises(ValueError):
        plan[::0]
    for index in (14, -15):
        with pytest.raises(IndexError, match="out of range"):
            plan[index]
    assert str(plan) == plan.text and str(plan[0]) == plan[0].text
    assert sum(1 for _ in plan) == 14  # each iteration starts afresh
    assert list(plan) and [s.text for s in plan] == [s.text for s in plan]


def test_value_classes_say_what_they_are(ais_map, paper):
    outcome = sewerplan.plan(paper)
    assert repr(ais_map) == "<SewerMap ais-testbed manholes=12 pipes=14 points=1>"
    assert repr(paper) == ("<Mission paper-section-6 map='ais-testbed' start='pipe P12' tasks=3 "
                           "profile='makro-1.1'>")
    assert repr(outcome.plan) == ("<Plan mission='paper-section-6' steps=14 "
                                  "first='DRIVE_PIPE_TO_MANHOLE P12 M2'>")
    assert repr(outcome).startswith("<PlanOutcome steps=14 cost_s=585.377 energy_wh=19.51")
    assert repr(sewerplan.check(outcome.plan)) == "<ValidationReport valid=True total_cost_s=585.378>"
    assert repr(ais_map.manholes[0]) == "<Manhole M1 slots=1 exit=True>"
    assert repr(paper.tasks[0]) == "<Task sample kind='take_water_sample'>"
    assert repr(sewerplan.RobotProfile("makro-plus")).startswith("<RobotProfile makro-plus ")
    assert repr(sewerplan.Replanner(paper).plan()).startswith(
        "<PlanResponse decision='follow-plan' steps=14 cost_s=585.377")


def reprs_of(value, seen, depth=0):
    """The repr of `value` and of every value reachable through its public attributes."""
    if depth > 3 or isinstance(value, (str, int, float, bool, type(None))):
        return
    if any(value is s for s in seen):
        return
    seen.append(value)  # held, so that no later value reuses its id
    if isinstance(value, (list, tuple)):
        for item in value[:3]:
            reprs_of(item, seen, depth + 1)
        return
    if isinstance(value, dict):
        return
    yield_repr = repr(value)
    assert not DEFAULT_REPR.search(yield_repr), yield_repr
    if isinstance(value, sewerplan.Plan):
        return  # its steps and actions are reached through the lists below
    for name in dir(type(value)):
        if name.startswith("_") or callable(getattr(value, name)):
            continue
        reprs_of(getattr(value, name), seen, depth + 1)


def test_no_default_reprs_anywhere(ais_map, paper):
    outcome = sewerplan.plan(paper)
    faults = sewerplan.random_faults(paper, seed=3, obstacles_per_km=200)
    simulation = sewerplan.simulate(paper, faults)
    campaign = sewerplan.run_campaign(paper, runs=2, guard=False)
    replanner = sewerplan.Replanner(paper)
    seen = []
    for value in [ais_map, paper, outcome, outcome.plan.steps, outcome.plan.actions,
                  sewerplan.check(outcome.plan), faults, simulation,
                  [e.what for e in simulation.events], campaign, replanner, replanner.plan(),
                  sewerplan.CancelToken(), sewerplan.Halter(), sewerplan.RobotProfile()]:
        reprs_of(value, seen)
    assert len(seen) > 30
    assert {type(e.what).__name__ for e in simulation.events} >= {
        "PlanEvent", "ActionEvent", "JobEvent", "MissionEndEvent"}


def public_api():
    for name in sorted(dir(sewerplan)):
        if not name.startswith("_"):
            yield name, getattr(sewerplan, name)


def test_every_public_class_function_method_and_field_has_a_docstring():
    def documented(function):
        # pybind11 writes the signature as the docstring's first line; the text is after it.
        doc = inspect.getdoc(function) or ""
        lines = [l for l in doc.splitlines() if l.strip() and not re.match(r"^\w+\(.*\)( -> .*)?$", l)]
        return bool(lines)

    missing = []
    for name, value in public_api():
        if inspect.ismodule(value) or not callable(value):
            continue
        if not documented(value):
            missing.append(name)
        if isinstance(value, type) and not issubclass(value, BaseException):
            for attr, member in vars(value).items():
                if attr.startswith("_") and attr not in ("__init__", "__getitem__", "__len__",
                                                         "__iter__"):
                    continue
                if attr == "__init__" and hasattr(value, "__members__"):
                    continue  # an enum's: pybind11's own, from its value
                if callable(member) and not documented(getattr(value, attr)):
                    missing.append(f"{name}.{attr}")
                if isinstance(member, property) and not attr.startswith("_") and not (
                        hasattr(value, "__members__") and attr == "value"):
                    doc = (member.__doc__ or "").strip()
                    if not doc or re.match(r"^\((self|arg0): .*\) -> ", doc):
                        missing.append(f"{name}.{attr}")  # a field: its meaning and unit
    assert missing == []
