# SPDX-License-Identifier: MIT
# Maps and missions from Python: reading, converting, building, and errors naming file and line.
import json

import pytest

import sewerplan
from conftest import AIS, SOURCE


def test_reads_the_ais_map(ais_map):
    assert ais_map.name == "ais-testbed"
    assert (ais_map.manhole_count, ais_map.pipe_count) == (12, 14)
    assert ais_map.exits == ["M1", "M4", "M10", "M12"]
    assert ais_map.kind_of("M3") == "manhole"
    assert ais_map.kind_of("P4") == "pipe"
    assert ais_map.kind_of("W1") == "point"
    assert ais_map.kind_of("nothing") is None
    p12 = next(p for p in ais_map.pipes if p["name"] == "P12")
    assert p12["to"] == "M2"


def test_converts_between_formats(ais_map, tmp_path):
    sewerplan.write_map(ais_map, str(tmp_path / "ais.sewer"))
    back = sewerplan.read_map(str(tmp_path / "ais.sewer"))
    assert (back.manhole_count, back.pipe_count) == (12, 14)
    assert sewerplan.parse_map(ais_map.to_json(), "ais.json") == ais_map
    imported = sewerplan.read_map(str(SOURCE / "datasets" / "isybau" / "street-2017.xml"))
    assert imported.manhole_count > 0


def test_a_read_only_format_is_not_written(ais_map, tmp_path):
    with pytest.raises(sewerplan.Error) as error:
        sewerplan.write_map(ais_map, str(tmp_path / "x.inp"), format="swmm")
    assert error.value.code == "unsupported-format"


def test_a_broken_map_names_file_and_json_path():
    with pytest.raises(sewerplan.Error) as error:
        sewerplan.read_map(str(SOURCE / "tests" / "data" / "json" / "broken.json"))
    assert error.value.code == "invalid-map"
    where = {(d.path, d.severity) for d in error.value.diagnostics}
    assert ("$.pipes[1].length_m", "error") in where
    assert all(d.file.endswith("broken.json") for d in error.value.diagnostics)


def test_a_syntax_error_names_the_line():
    text = '{\n  "format": "sewerplan-map",\n  "version": 1,\n  oops\n}\n'
    with pytest.raises(sewerplan.Error) as error:
        sewerplan.parse_map(text, "bad.json")
    assert error.value.code == "parse"
    assert [(d.file, d.line) for d in error.value.diagnostics] == [("bad.json", 4)]


def test_a_missing_file_is_an_io_error():
    with pytest.raises(sewerplan.Error) as error:
        sewerplan.read_map("no/such/map.json")
    assert error.value.code == "io"
    assert "no/such/map.json" in error.value.message


def test_reads_and_writes_mission_json(ais_map, paper, tmp_path):
    assert paper.name == "paper-section-6"
    assert [t.name for t in paper.tasks] == ["sample", "inspect", "end"]
    assert paper.tasks[2].final
    assert paper.start == "pipe P12"
    path = tmp_path / "paper.json"
    sewerplan.write_mission(paper, str(path))
    back = sewerplan.read_mission(ais_map, str(path))
    assert back.to_json() == paper.to_json()
    assert json.loads(back.to_json())["format"] == "sewerplan-mission"


def test_a_mission_that_cannot_be_written_is_an_io_error_naming_the_file(paper):
    # Issue 30: every write checked, through core/output_file.h.
    with pytest.raises(sewerplan.Error) as error:
        sewerplan.write_mission(paper, "/dev/full")
    assert error.value.code == "io"
    assert "cannot write /dev/full: No space left on device" in error.value.message


def test_builds_a_mission_from_python(ais_map, paper):
    profile = sewerplan.RobotProfile("makro-1.1")
    built = sewerplan.mission(
        ais_map, name="paper-section-6", start="P12", profile=profile,
        tasks=[sewerplan.take_water_sample("W1", name="sample"),
               sewerplan.inspect_pipe("P4", name="inspect"),
               sewerplan.go_to("P9", name="end", final=True)],
        exits=["M1", "M10"], battery_reserve=0.2)
    assert [t.kind for t in built.tasks] == ["take_water_sample", "inspect_pipe", "go_to"]
    assert built.exits == ["M1", "M10"]
    assert built.profile.battery_wh == profile.battery_wh
    assert sewerplan.plan(built).cost_s == sewerplan.plan(paper).cost_s


def test_a_bad_mission_names_the_json_path(ais_map):
    with pytest.raises(sewerplan.Error) as error:
        sewerplan.mission(ais_map, start="M1", tasks=[{"type": "inspect_pipe", "pipe": "P99"}])
    assert error.value.code == "invalid-mission"
    assert any(d.path == "$.tasks[0].pipe" for d in error.value.diagnostics)
    with pytest.raises(sewerplan.Error) as error:
        sewerplan.mission(ais_map, start="nowhere")
    assert error.value.code == "invalid-mission"
    assert "nowhere" in error.value.message


def test_profiles():
    plus = sewerplan.RobotProfile("makro-plus")
    assert plus.speed_mps == 0.6
    assert "makro-1.1" in sewerplan.builtin_profile_names()
    with pytest.raises(sewerplan.Error) as error:
        sewerplan.RobotProfile("no-such-robot")
    assert error.value.code == "invalid-profile"
