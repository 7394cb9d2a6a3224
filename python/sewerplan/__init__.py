# SPDX-License-Identifier: MIT
"""sewerplan: planning and replanning for autonomous sewer-inspection robots (docs/python.md).

    import sewerplan
    m = sewerplan.read_map("datasets/ais-testbed/map.json")
    mission = sewerplan.read_mission(m, "datasets/ais-testbed/missions/paper.json")
    outcome = sewerplan.plan(mission, time_limit_s=1.0)
    print(outcome.plan.text, outcome.cost_s, outcome.energy_wh)

Errors are sewerplan.Error exceptions, one subclass per error code (ParseError, NoPlanError,
...; grouped as the CLI's exit codes: InvalidInputError, IoError, SearchStoppedError), with .code
("parse", "no-plan", ...), .exit_code, .message and .diagnostics (each naming its .file and .line
or JSON .path).
"""
import json as _json

from ._sewerplan import *  # noqa: F401,F403
from ._sewerplan import InvalidMissionError, Mission, RobotProfile, SewerMap
from ._sewerplan import __version__  # noqa: F401 (project(sewerplan VERSION) in CMakeLists.txt)

__all__ = [name for name in dir() if not name.startswith("_")]


def _place(map_, place):
    """A place of the mission format from a name (a manhole, pipe or point of `map_`) or a dict."""
    if isinstance(place, dict):
        return place
    kind = map_.kind_of(place)
    if kind is None:
        message = f"no manhole, pipe or point named '{place}' in map {map_.name}"
        error = InvalidMissionError(message)
        error.code, error.exit_code = InvalidMissionError.code, InvalidMissionError.exit_code
        error.message, error.diagnostics = message, []
        raise error
    return {kind: place}


def go_to(at, name=None, final=False):
    """A go-to task: reach `at` (a manhole, pipe or point name, or a place dict)."""
    return {"type": "go_to", "at": at, "name": name, "final": final}


def inspect_pipe(pipe, name=None):
    """Drive the whole pipe while scanning it."""
    return {"type": "inspect_pipe", "pipe": pipe, "name": name}


def take_water_sample(at, name=None):
    """Drive to `at` (a point or pipe name, or a place dict) and take a water sample."""
    return {"type": "take_water_sample", "at": at, "name": name}


def mission(map, *, start, tasks=(), exits="map", profile="makro-1.1", battery_reserve=0.2,
            name="mission", closed_pipes=()):
    """Builds a Mission on `map` from Python values, checked as a mission file is.

    start: a manhole, pipe or point name (or a place dict); tasks: go_to(), inspect_pipe(),
    take_water_sample() (or task dicts of the mission format); exits: manhole names, "map" or
    "all"; profile: a built-in profile's name, a RobotProfile or a profile dict.
    """
    if isinstance(profile, RobotProfile):
        profile = profile.to_dict()
    doc_tasks = []
    for task in tasks:
        task = {k: v for k, v in task.items() if v is not None}
        if "at" in task:
            task["at"] = _place(map, task["at"])
        if task.get("final") is False:
            del task["final"]
        doc_tasks.append(task)
    doc = {
        "format": "sewerplan-mission",
        "version": 1,
        "name": name,
        "profile": profile,
        "start": _place(map, start),
        "tasks": doc_tasks,
        "exits": exits if isinstance(exits, str) else list(exits),
        "battery_reserve": battery_reserve,
    }
    if closed_pipes:
        doc["closed"] = {"pipes": list(closed_pipes)}
    return Mission.from_json(map, _json.dumps(doc), "<python mission " + name + ">")


def write_mission(mission, path):
    """Writes a mission in its JSON format, atomically; a failed write raises Error naming the
    file (write_text_file, core/output_file.h)."""
    write_text_file(str(path), mission.to_json())
