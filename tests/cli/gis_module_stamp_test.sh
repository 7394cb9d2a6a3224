#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The GIS module's ABI stamp (sewerplan/modules/gis_table.h): a sewerplan command beside a module of
# another build (the same source and version, another build id) refuses it with an error that
# names the module and both stamps (exit 1, no crash), and beside its own module writes GeoJSON.
# Usage: gis_module_stamp_test.sh PATH_TO_SEWERPLAN ITS_MODULE OTHER_BUILDS_MODULE SOURCE_DIR
set -euo pipefail
sp=$1
module=$2
other=$3
src=$4
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
data=$src/datasets/ais-testbed
"$sp" convert --map "$data/map.json" --crs EPSG:25832 -o "$tmp/map.json" > /dev/null

# The build tree's layout, in a scratch tree: the command, and a module where it looks for it.
relative=$(realpath --relative-to="$(dirname "$sp")" "$module")
mkdir -p "$tmp/tree/bin"
cp "$sp" "$tmp/tree/bin/sewerplan"
placed="$tmp/tree/bin/$relative"
mkdir -p "$(dirname "$placed")"

cp "$other" "$placed"
status=0
"$tmp/tree/bin/sewerplan" export-geojson --map "$tmp/map.json" -o "$tmp/other.geojson" \
  2> "$tmp/other.err" || status=$?
[ "$status" -eq 1 ] || { echo "FAIL: a module of another build: exit $status, want 1"; cat "$tmp/other.err"; exit 1; }
[ ! -e "$tmp/other.geojson" ] || { echo "FAIL: GeoJSON written through a module of another build"; exit 1; }
want='export-geojson needs GDAL and PROJ, but the gis module .*/sewerplan_gis\.so is of another build or configuration of sewerplan \(its ABI stamp: "sewerplan [0-9.]+ build 0000000000000000; sizes GisTable [0-9]+ SewerMap [0-9]+ .*", this sewerplan.s: "sewerplan [0-9.]+ build [0-9a-f]{16}; sizes GisTable [0-9]+ .*"\)'
grep -Eq "$want" "$tmp/other.err" || { echo "FAIL: unclear error:"; cat "$tmp/other.err"; exit 1; }
if grep -q 'build 0000000000000000; sizes.*this sewerplan.s: "sewerplan [0-9.]* build 0000000000000000' "$tmp/other.err"; then
  echo "FAIL: the command's own build id is the other build's"; exit 1
fi

cp "$module" "$placed"
"$tmp/tree/bin/sewerplan" export-geojson --map "$tmp/map.json" -o "$tmp/own.geojson" > /dev/null
grep -q '"FeatureCollection"' "$tmp/own.geojson" || { echo "FAIL: no GeoJSON through its own module"; exit 1; }
echo "GIS module stamp: ok"
