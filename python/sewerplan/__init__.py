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
from typing import Any as _Any, Iterable as _Iterable, Optional as _Optional, Union as _Union

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


def go_to(at: _Union[str, dict], name: _Optional[str] = None, final: bool = False) -> dict:
    """A go-to task for mission(): reach `at` (a manhole, pipe or point name, or a place dict);
    final: done last, the mission ends there."""
    return {"type": "go_to", "at": at, "name": name, "final": final}


def inspect_pipe(pipe: str, name: _Optional[str] = None) -> dict:
    """An inspection task for mission(): drive the whole pipe while scanning it."""
    return {"type": "inspect_pipe", "pipe": pipe, "name": name}


def take_water_sample(at: _Union[str, dict], name: _Optional[str] = None) -> dict:
    """A sampling task for mission(): drive to `at` (a point or pipe name, or a place dict) and
    take a water sample."""
    return {"type": "take_water_sample", "at": at, "name": name}


def mission(map: SewerMap, *, start: _Union[str, dict], tasks: _Iterable[dict] = (),
            exits: _Union[str, _Iterable[str]] = "map",
            profile: _Union[str, RobotProfile, dict] = "makro-1.1", battery_reserve: float = 0.2,
            name: str = "mission", closed_pipes: _Iterable[str] = ()) -> Mission:
    """Builds a Mission on `map` from Python values, checked as a mission file is.

    start: a manhole, pipe or point name (or a place dict); tasks: go_to(), inspect_pipe(),
    take_water_sample() (or task dicts of the mission format); exits: manhole names, "map" or
    "all"; profile: a built-in profile's name, a RobotProfile or a profile dict;
    battery_reserve: the fraction of the battery kept for the way out (0 to 1); closed_pipes:
    pipe names the robot must not use. Raises InvalidMissionError naming the JSON path.
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


def write_mission(mission: Mission, path: _Any) -> None:
    """Writes a mission in its JSON format, atomically; a failed write raises IoError naming the
    file (write_text_file, core/output_file.h); path: a str or os.PathLike."""
    write_text_file(str(path), mission.to_json())
