#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The GIS module is loaded only by the commands that need it (sewerplan/modules/gis_table.h): `--version`,
# `plan` and `validate` on a JSON map never load GDAL or PROJ (the dynamic loader's own trace,
# LD_DEBUG=files), export-geojson does, and writes its file. A sewerplan whose module is missing (the
# executable copied alone) still plans, and its export-geojson is an error naming the missing module
# with the usage of a failed command (exit 1, no crash); so is a GeoJSON given as --map.
# Usage: lazy_gis_test.sh PATH_TO_SEWERPLAN SOURCE_DIR
set -euo pipefail
sp=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
data=$src/datasets/ais-testbed
plan=(plan --map "$data/map.json" --mission "$data/missions/paper.json" -q)

source "$(dirname "$0")/loader_trace.sh"  # loaded OUT COMMAND...
for run in version plan validate; do
  case $run in
    version) args=(--version) ;;
    plan) args=("${plan[@]}") ;;
    validate) args=(validate --map "$data/map.json") ;;
  esac
  loaded "$tmp/$run.trace" "$sp" "${args[@]}"
  grep -q 'file=libc\.so' "$tmp/$run.trace" || { echo "FAIL: no loader trace for $run"; exit 1; }
  if grep -Eq 'file=.*(libgdal|libproj|sewerplan_gis)' "$tmp/$run.trace"; then
    echo "FAIL: sewerplan $run loaded GDAL, PROJ or the GIS module:"
    grep -E 'file=.*(libgdal|libproj|sewerplan_gis)' "$tmp/$run.trace" | head -5
    exit 1
  fi
done

"$sp" convert --map "$data/map.json" --crs EPSG:25832 -o "$tmp/map.json" > /dev/null
loaded "$tmp/export.trace" "$sp" export-geojson --map "$tmp/map.json" -o "$tmp/net.geojson"
grep -q 'file=.*sewerplan_gis\.so' "$tmp/export.trace" || {
  echo "FAIL: export-geojson did not load the GIS module"; exit 1; }
grep -q 'file=.*libgdal' "$tmp/export.trace" || { echo "FAIL: export-geojson did not load GDAL"; exit 1; }
grep -q '"FeatureCollection"' "$tmp/net.geojson" || { echo "FAIL: no GeoJSON written"; exit 1; }

# The executable alone, without its lib/sewerplan/sewerplan_gis.so.
mkdir -p "$tmp/alone/bin"
cp "$sp" "$tmp/alone/bin/sewerplan"
"$tmp/alone/bin/sewerplan" "${plan[@]}" > "$tmp/alone.plan"
cmp -s "$tmp/alone.plan" <("$sp" "${plan[@]}") || { echo "FAIL: the plan differs without the module"; exit 1; }
status=0
"$tmp/alone/bin/sewerplan" export-geojson --map "$tmp/map.json" -o "$tmp/alone.geojson" \
  2> "$tmp/alone.err" || status=$?
[ "$status" -eq 1 ] || { echo "FAIL: export-geojson without the module exited $status, want 1"; cat "$tmp/alone.err"; exit 1; }
grep -q "export-geojson needs GDAL and PROJ, but the gis module is missing (looked for .*/lib/sewerplan/sewerplan_gis.so" \
  "$tmp/alone.err" || { echo "FAIL: unclear error:"; cat "$tmp/alone.err"; exit 1; }
# A GeoJSON given as --map (issue 31) is a GIS source, whatever its name: without the module, an
# error that says what is missing, not "missing required field 'format'".
cp "$tmp/net.geojson" "$tmp/exported.json"
for geojson in "$tmp/net.geojson" "$tmp/exported.json"; do
  status=0
  "$tmp/alone/bin/sewerplan" info --map "$geojson" > "$tmp/alone.out" 2>&1 || status=$?
  [ "$status" -ne 0 ] || { echo "FAIL: info on $geojson without the module succeeded"; exit 1; }
  grep -q "reading $geojson needs GDAL and PROJ, but the gis module is missing" "$tmp/alone.out" ||
    { echo "FAIL: unclear error for $geojson:"; cat "$tmp/alone.out"; exit 1; }
done
echo "lazy GIS: ok"
