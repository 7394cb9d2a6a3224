# SPDX-License-Identifier: MIT
# GIS sources from Python: a GeoPackage written by GDAL's own ogr2ogr from our export-geojson output
# reads back through sewerplan.read_map as the sewerplan command reads it (gis/map_source.h), and
# gis_fields overrides its field mapping. Skipped only where the module has no GIS (has_gis) or
# there is no ogr2ogr (Debian gdal-bin) or sewerplan command (SEWERPLAN_CLI) to write the source.
import os
import shutil
import subprocess

import pytest

import sewerplan
from conftest import AIS

CRS = "EPSG:25832"


@pytest.fixture(scope="module")
def gis_source(tmp_path_factory):
    if not sewerplan.has_gis:
        pytest.skip("the module is built without GIS (SEWERPLAN_WITH_GIS=OFF)")
    ogr2ogr = shutil.which("ogr2ogr")
    if ogr2ogr is None:
        pytest.skip("no ogr2ogr (Debian gdal-bin) to write a GeoPackage")
    cli = os.environ.get("SEWERPLAN_CLI")
    if not cli or not os.access(cli, os.X_OK):
        pytest.skip("no sewerplan command (SEWERPLAN_CLI) to export the GeoJSON")
    tmp = tmp_path_factory.mktemp("gis")
    original = tmp / "original.json"
    run = lambda *args: subprocess.run([str(a) for a in args], check=True, capture_output=True)
    run(cli, "convert", "--map", AIS / "map.json", "--crs", CRS, "-o", original)
    run(cli, "export-geojson", "--map", original, "-o", tmp / "net.geojson")
    gpkg = tmp / "net.gpkg"
    run(ogr2ogr, "-f", "GPKG", gpkg, tmp / "net.geojson", "-t_srs", CRS,
        "-where", "layer = 'manhole'", "-nln", "manholes")
    run(ogr2ogr, "-f", "GPKG", "-update", gpkg, tmp / "net.geojson", "-t_srs", CRS,
        "-where", "layer = 'pipe'", "-nln", "pipes")
    return original, gpkg


def test_a_geopackage_reads_back_as_the_network_it_came_from(gis_source):
    original, gpkg = gis_source
    a = sewerplan.read_map(str(original))
    b = sewerplan.read_map(str(gpkg))
    assert (b.manhole_count, b.pipe_count, b.crs) == (12, 14, CRS)
    assert b.exits == a.exits
    for x, y in zip(sorted(a.manholes, key=lambda m: m.name), sorted(b.manholes, key=lambda m: m.name)):
        assert x.name == y.name
        assert abs(x.position.x_m - y.position.x_m) < 0.01
        assert abs(x.position.y_m - y.position.y_m) < 0.01
        assert abs(x.diameter_m - y.diameter_m) < 1e-6
        assert x.slot_count == y.slot_count
    ends = lambda m: sorted((p["name"], p["from"], p["to"]) for p in m.pipes)
    assert ends(b) == ends(a)
    # The GIS map plans (the paper's mission less the water sample: GeoJSON carries no inspection
    # points; nor slot azimuths, so the route may pass the manholes' slots differently).
    mission = sewerplan.mission(
        b, name="gis", start="P12", profile="makro-1.1", exits="map",
        tasks=[sewerplan.inspect_pipe("P4", name="inspect"),
               sewerplan.go_to("P9", name="end", final=True)])
    outcome = sewerplan.plan(mission, time_limit_s=1.0)
    assert len(outcome.plan) > 0 and not outcome.dropped
    assert any(step.task == "inspect" for step in outcome.plan.steps)


def test_gis_fields_overrides_the_field_mapping(gis_source, tmp_path):
    _, gpkg = gis_source
    # No exit and no type field: every manhole is an exit (docs/formats/gis-layers.md).
    mapping = tmp_path / "all-exits.json"
    mapping.write_text('{"manholes": {"exit": null, "type": null}}')
    assert len(sewerplan.read_map(str(gpkg)).exits) == 4
    assert len(sewerplan.read_map(str(gpkg), gis_fields=str(mapping)).exits) == 12


def test_a_bad_field_mapping_names_its_file(gis_source, tmp_path):
    _, gpkg = gis_source
    with pytest.raises(sewerplan.Error) as error:
        sewerplan.read_map(str(gpkg), gis_fields=str(tmp_path / "missing.json"))
    assert error.value.code == "io" and "missing.json" in error.value.message
    bad = tmp_path / "bad.json"
    bad.write_text('{"pipes": {"height": {"field": "dn", "unit": "furlong"}}}')
    with pytest.raises(sewerplan.Error) as error:
        sewerplan.read_map(str(gpkg), gis_fields=str(bad))
    assert error.value.code == "parse"
    assert [(d.file, d.path) for d in error.value.diagnostics] == [
        (str(bad), "$.pipes.height.unit")]


def test_gis_fields_for_a_map_that_is_no_gis_source_is_an_error(tmp_path):
    if not sewerplan.has_gis:
        pytest.skip("the module is built without GIS")
    mapping = tmp_path / "fields.json"
    mapping.write_text("{}")
    with pytest.raises(sewerplan.Error) as error:
        sewerplan.read_map(str(AIS / "map.json"), gis_fields=str(mapping))
    assert error.value.code == "invalid-argument" and "not a GIS source" in error.value.message
