#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Acceptance (issue 18): a GeoPackage, and a Shapefile directory, written by GDAL's own ogr2ogr from
# our export-geojson output import back to the same network: every manhole (position within 1 cm,
# invert, diameter, depth, exit, slot count) and every pipe (its manholes, length, clear size,
# height, shape), and the CRS. Every other field (pipe-end inverts, slot azimuths, shaft sizes,
# inspection points, findings) is compared by gis_lossless_round_trip.sh (issue 31).
# Then the command line on GIS sources: validate --json, a file GDAL cannot open, a pipe naming a
# manhole the layer lacks.
# Usage: gis_round_trip.sh PATH_TO_SEWERPLAN SOURCE_DIR PATH_TO_OGR2OGR
set -euo pipefail
sp=$1
src=$2
ogr2ogr=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
map=$src/datasets/ais-testbed/map.json
crs=EPSG:25832

# split_layers FORMAT OUT [MANHOLE_FILTER]: the GeoJSON's manholes and pipes as two layers of OUT,
# back in the map's CRS (MANHOLE_FILTER: an SQL condition more on the manholes).
split_layers() {
  local format=$1 out=$2 filter=${3:+ AND $3} update=()
  [ "$format" = GPKG ] && update=(-update)
  "$ogr2ogr" -f "$format" "$out" "$tmp/net.geojson" -t_srs "$crs" \
    -where "layer = 'manhole'$filter" -nln manholes
  "$ogr2ogr" -f "$format" "${update[@]}" "$out" "$tmp/net.geojson" -t_srs "$crs" \
    -where "layer = 'pipe'" -nln pipes
}
# expect_exit CODE OUT COMMAND...: run COMMAND, its standard output to OUT; fail unless it exits CODE.
expect_exit() {
  local want=$1 out=$2 status=0
  shift 2
  "$@" > "$out" || status=$?
  [ "$status" -eq "$want" ] || { echo "FAIL: $* exited $status, want $want"; cat "$out"; exit 1; }
}

"$sp" convert --map "$map" --crs "$crs" -o "$tmp/original.json"
"$sp" export-geojson --map "$tmp/original.json" -o "$tmp/net.geojson"
split_layers GPKG "$tmp/net.gpkg"
mkdir "$tmp/shp"
split_layers "ESRI Shapefile" "$tmp/shp"

for source in "$tmp/net.gpkg" "$tmp/shp"; do
  "$sp" convert --map "$source" -o "$tmp/back.json"
  /usr/bin/python3 - "$tmp/original.json" "$tmp/back.json" "$source" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
source = sys.argv[3]
problems = []
def close(x, y, tol=1e-6):
    return (x is None and y is None) or (x is not None and y is not None and abs(x - y) <= tol)
if a.get("crs") != b.get("crs"):
    problems.append(f"crs {a.get('crs')} != {b.get('crs')}")
ma = {m["name"]: m for m in a["manholes"]}
mb = {m["name"]: m for m in b["manholes"]}
if set(ma) != set(mb):
    problems.append(f"manholes differ: {sorted(set(ma) ^ set(mb))}")
for name in set(ma) & set(mb):
    x, y = ma[name], mb[name]
    if not (close(x["x_m"], y["x_m"], 0.01) and close(x["y_m"], y["y_m"], 0.01)
            and close(x.get("z_m", 0), y.get("z_m", 0))):
        problems.append(f"manhole {name}: position {x['x_m'], x['y_m']} != {y['x_m'], y['y_m']}")
    for key in ("diameter_m", "depth_m"):
        if not close(x.get(key), y.get(key)):
            problems.append(f"manhole {name}: {key} {x.get(key)} != {y.get(key)}")
    if bool(x.get("exit", False)) != bool(y.get("exit", False)):
        problems.append(f"manhole {name}: exit {x.get('exit')} != {y.get('exit')}")
    if len(x["slots"]) != len(y["slots"]):
        problems.append(f"manhole {name}: {len(x['slots'])} slots != {len(y['slots'])}")
pa = {p["name"]: p for p in a["pipes"]}
pb = {p["name"]: p for p in b["pipes"]}
if set(pa) != set(pb):
    problems.append(f"pipes differ: {sorted(set(pa) ^ set(pb))}")
for name in set(pa) & set(pb):
    x, y = pa[name], pb[name]
    for key in ("from", "to", "shape"):
        if x.get(key) != y.get(key):
            problems.append(f"pipe {name}: {key} {x.get(key)} != {y.get(key)}")
    for key in ("length_m", "diameter_m", "height_m"):
        if not close(x.get(key), y.get(key)):
            problems.append(f"pipe {name}: {key} {x.get(key)} != {y.get(key)}")
for p in problems[:20]:
    print(f"{source}: {p}")
if problems:
    sys.exit(1)
print(f"{source}: {len(mb)} manholes and {len(pb)} pipes back as they were")
PY
done

# The command line on GIS sources.
"$sp" validate --map "$tmp/net.gpkg" --json > "$tmp/valid.json"
"$sp" info --map "$tmp/shp/pipes.shp" > /dev/null
echo "not a GeoPackage" > "$tmp/bad.gpkg"
expect_exit 1 "$tmp/bad.json" "$sp" validate --map "$tmp/bad.gpkg" --json
split_layers GPKG "$tmp/no-m1.gpkg" "name <> 'M1'"
expect_exit 1 "$tmp/no-m1.json" "$sp" validate --map "$tmp/no-m1.gpkg" --json
# --gis-fields FILE: a mapping file other than the sidecar. Without exit and type fields every
# manhole is an exit; a missing file is an I/O error (3), a malformed one invalid input (1), both
# naming the file; a mapping for a map that is no GIS source a usage error (2).
echo '{"manholes": {"exit": null, "type": null}}' > "$tmp/all-exits.json"
expect_exit 0 "$tmp/exits.json" "$sp" info --map "$tmp/net.gpkg" --json
expect_exit 0 "$tmp/all-exits.out.json" "$sp" info --map "$tmp/net.gpkg" --gis-fields "$tmp/all-exits.json" --json
# (The GeoJSON does not carry inspection points: a mission without the water sample.)
grep -v '"W1"' "$src/datasets/ais-testbed/missions/paper.json" > "$tmp/no-sample.json"
expect_exit 0 "$tmp/all-exits.plan.json" "$sp" plan --map "$tmp/shp" --gis-fields "$tmp/all-exits.json" \
  --mission "$tmp/no-sample.json" --json
expect_exit 3 "$tmp/missing.json" "$sp" info --map "$tmp/net.gpkg" --gis-fields "$tmp/nothing.json" --json
echo '{"pipes": {"height": {"field": "dn", "unit": "furlong"}}}' > "$tmp/inch.json"
expect_exit 1 "$tmp/malformed.json" "$sp" validate --map "$tmp/net.gpkg" --gis-fields "$tmp/inch.json" --json
echo '{"pipes": ' > "$tmp/cut.json"
expect_exit 1 "$tmp/cut.out.json" "$sp" convert --map "$tmp/net.gpkg" --gis-fields "$tmp/cut.json" -o "$tmp/x.json" --json
expect_exit 2 "$tmp/not-gis.json" "$sp" info --map "$map" --gis-fields "$tmp/all-exits.json" --json
# A campaign on a Shapefile directory (no one file to fingerprint): the map as read is its identity,
# so a field mapping that changes the network changes the fingerprint and the shards do not merge.
expect_exit 0 "$tmp/campaign-a.out" "$sp" campaign --map "$tmp/shp" --mission "$tmp/no-sample.json" \
  --runs 2 --seed 1 --jobs 1 -q -o "$tmp/campaign-a"
expect_exit 0 "$tmp/campaign-b.out" "$sp" campaign --map "$tmp/shp" --gis-fields "$tmp/all-exits.json" \
  --mission "$tmp/no-sample.json" --runs 2 --seed 1 --jobs 1 -q -o "$tmp/campaign-b"
/usr/bin/python3 - "$tmp" <<'PY'
import json, sys
tmp = sys.argv[1]
load = lambda name: json.load(open(f"{tmp}/{name}"))
assert len(load("exits.json")["exits"]) == 4, load("exits.json")
assert len(load("all-exits.out.json")["exits"]) == 12, load("all-exits.out.json")
assert load("all-exits.plan.json")["steps"], load("all-exits.plan.json")
missing = load("missing.json")["error"]
assert missing["code"] == "io" and missing["message"] == f"--gis-fields {tmp}/nothing.json: no such file", missing
malformed = load("malformed.json")
assert malformed["error"]["code"] == "parse", malformed
assert [e["where"] for e in malformed["errors"]] == [f"{tmp}/inch.json:$.pipes.height.unit"], malformed
cut = load("cut.out.json")["error"]
assert cut["code"] == "parse" and cut["diagnostics"][0]["where"].startswith(f"{tmp}/cut.json:"), cut
not_gis = load("not-gis.json")["error"]
assert not_gis["code"] == "usage" and "is not a GIS source" in not_gis["message"], not_gis
print("--gis-fields: a mapping file applied; missing, malformed and misplaced ones name the file")
fingerprint = lambda d: json.load(open(f"{tmp}/{d}/campaign.json"))["map_fingerprint"]
assert fingerprint("campaign-a") != fingerprint("campaign-b"), "a field mapping left the map's fingerprint"
print("campaign: a Shapefile directory is read, and its field mapping is part of the map's identity")
PY
/usr/bin/python3 - "$tmp/valid.json" "$tmp/bad.json" "$tmp/no-m1.json" <<'PY'
import json, sys
valid, bad, no_m1 = (json.load(open(p)) for p in sys.argv[1:4])
assert valid["valid"] is True and valid["manholes"] == 12 and valid["pipes"] == 14, valid
assert bad["valid"] is False and bad["error"]["code"] == "parse", bad
assert "not a GeoJSON, GeoPackage or Shapefile GDAL can open" in bad["error"]["message"], bad
messages = [e["where"] + ": " + e["message"] for e in no_m1["errors"]]
assert any(m.endswith("pipe P12: field from: 'M1' names no manhole (by name of layer manholes)")
           and ":pipes: feature " in m for m in messages), messages
print("command line on GIS sources: as documented")
PY
