# SPDX-License-Identifier: MIT
# The exception hierarchy (one class per library error code, grouped as the CLI's exit codes) and
# sewerplan.__version__.
import pathlib
import re

import pytest

import sewerplan
from conftest import AIS, SOURCE
from test_planning import impossible

# docs/cli.md, "Exit codes": each library error code, its class and the CLI's exit code.
CLASSES = {
    "parse": ("ParseError", "InvalidInputError", 1),
    "invalid-map": ("InvalidMapError", "InvalidInputError", 1),
    "invalid-mission": ("InvalidMissionError", "InvalidInputError", 1),
    "invalid-profile": ("InvalidProfileError", "InvalidInputError", 1),
    "unsupported-format": ("UnsupportedFormatError", "InvalidInputError", 1),
    "invalid-argument": ("InvalidArgumentError", "Error", 2),
    "io": ("IoError", "Error", 3),
    "can-timeout": ("CanTimeoutError", "IoError", 3),
    "bus-error": ("BusError", "IoError", 3),
    "no-plan": ("NoPlanError", "Error", 4),
    "search-limit": ("SearchLimitError", "SearchStoppedError", 5),
    "cancelled": ("CancelledError", "SearchStoppedError", 5),
}


def test_one_class_per_error_code_grouped_by_exit_code():
    for code, (name, parent, exit_code) in CLASSES.items():
        cls = getattr(sewerplan, name)
        assert cls.__bases__[0] is getattr(sewerplan, parent), name
        assert issubclass(cls, sewerplan.Error) and issubclass(cls, RuntimeError)
        assert (cls.code, cls.exit_code) == (code, exit_code), name
        assert cls.__doc__ and f"'{code}'" in cls.__doc__, name
    assert sewerplan.InvalidInputError.exit_code == 1
    assert sewerplan.SearchStoppedError.exit_code == 5
    assert issubclass(sewerplan.InvalidArgumentError, ValueError)
    # Every error class the module has is in the table (a new error code gets its row).
    module_classes = {n for n, v in vars(sewerplan).items()
                      if isinstance(v, type) and issubclass(v, sewerplan.Error)}
    groups = {"Error", "InvalidInputError", "SearchStoppedError"}
    assert module_classes == {name for name, _, _ in CLASSES.values()} | groups
    assert sewerplan.Error.__module__ == "sewerplan"


def raised(call):
    with pytest.raises(sewerplan.Error) as error:
        call()
    return error.value


def test_each_failure_raises_its_class(ais_map, paper, tmp_path):
    cases = {
        "io": lambda: sewerplan.read_map(str(tmp_path / "missing.json")),
        "parse": lambda: sewerplan.parse_map("{", "m.json"),
        "invalid-map": lambda: sewerplan.read_map(str(SOURCE / "tests/data/json/broken.json")),
        "invalid-mission": lambda: sewerplan.mission(ais_map, start="nowhere"),
        "invalid-profile": lambda: sewerplan.RobotProfile("no-such-robot"),
        "unsupported-format": lambda: sewerplan.parse_map("", format="pdf"),
        "invalid-argument": lambda: sewerplan.plan(paper, algorithm="magic"),
        "no-plan": lambda: sewerplan.plan(impossible(ais_map)),
    }
    for code, call in cases.items():
        error = raised(call)
        name, _, exit_code = CLASSES[code]
        assert type(error) is getattr(sewerplan, name), code
        assert (error.code, error.exit_code) == (code, exit_code)
        assert error.message and str(error) == error.message
    cancelled = sewerplan.CancelToken()
    cancelled.cancel()
    with pytest.raises(sewerplan.SearchStoppedError) as error:
        sewerplan.plan(paper, algorithm="astar", cancel=cancelled)
    assert type(error.value) is sewerplan.CancelledError and error.value.exit_code == 5


def test_catching_a_group_or_a_builtin():
    with pytest.raises(sewerplan.InvalidInputError):
        sewerplan.parse_map("{", "m.json")
    with pytest.raises(ValueError):  # InvalidArgumentError is a ValueError too
        sewerplan.generate_network(5, topology="spiral")


def test_version_is_the_projects():
    cmake = (SOURCE / "CMakeLists.txt").read_text()
    version = re.search(r"project\(sewerplan VERSION ([0-9.]+)", cmake).group(1)
    assert sewerplan.__version__ == version
