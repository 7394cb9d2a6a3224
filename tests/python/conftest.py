# SPDX-License-Identifier: MIT
# The pytest suite of the Python module (ctest: python.pytest). PYTHONPATH names the build tree's
# python/ directory, SEWERPLAN_SOURCE_DIR the source tree (datasets/).
import os
import pathlib

import pytest

import sewerplan

SOURCE = pathlib.Path(os.environ.get("SEWERPLAN_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
AIS = SOURCE / "datasets" / "ais-testbed"


@pytest.fixture(scope="session")
def ais_map():
    return sewerplan.read_map(str(AIS / "map.json"))


@pytest.fixture(scope="session")
def paper(ais_map):
    return sewerplan.read_mission(ais_map, str(AIS / "missions" / "paper.json"))
