#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The corrected map out (issue 29; docs/cli.md): simulate --corrected-map on the AIS testbed's exact
# world writes the corrected map (equal to the map: every measured length is the map's), its
# discrepancy report (none) and the measurements; merge-measurements pools two missions' files
# (twice the count, half the variance), refuses a file of another map naming it, and every failed
# write exits 3 naming the file.
# Usage: measurements_test.sh PATH_TO_SEWERPLAN SOURCE_DIR
set -uo pipefail
sp=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
source "$(dirname "${BASH_SOURCE[0]}")/expect.sh"
expect_timeout=60  # a hang fails

ais=$src/datasets/ais-testbed/map.json
mission=$src/datasets/ais-testbed/missions/paper.json
export SOURCE_DATE_EPOCH=1765000000

expect 0 "corrected map .*/fixed.json: [1-9][0-9]* pipes measured, 0 discrepancies" -- \
  "$sp" simulate --map "$ais" --mission "$mission" -q --corrected-map "$tmp/fixed.json"
check "the three files are written" test -s "$tmp/fixed.json" -a -s "$tmp/fixed.discrepancies.json" \
  -a -s "$tmp/fixed.measurements.json"
check "the report lists no discrepancy" grep -q '"discrepancies": \[\]' "$tmp/fixed.discrepancies.json"
check "the provenance is the profile, the mission and SOURCE_DATE_EPOCH's date" \
  grep -q '"date": "2025-12-06T05:46:40Z"' "$tmp/fixed.measurements.json"
# The corrected map of an exact world is the map: the same JSON once both are written by us.
"$sp" convert --map "$ais" -o "$tmp/ais.json" >/dev/null
check "the corrected map equals the map" cmp -s "$tmp/ais.json" "$tmp/fixed.json"
# Same inputs, same files.
"$sp" simulate --map "$ais" --mission "$mission" -q --corrected-map "$tmp/again.json" >/dev/null
check "deterministic" cmp -s "$tmp/fixed.measurements.json" "$tmp/again.measurements.json"

# Two missions pooled: twice the measurements of each pipe, half the variance.
expect 0 "merged 2 files \(2 missions\)" -- "$sp" merge-measurements --map "$ais" \
  "$tmp/fixed.measurements.json" "$tmp/again.measurements.json" -o "$tmp/merged.json" \
  --corrected-map "$tmp/merged-map.json"
check "counts doubled" grep -q '"count": 2' "$tmp/merged.json"
v1=$(grep -m1 -o '"variance_m2": [0-9.e-]*' "$tmp/fixed.measurements.json" | cut -d' ' -f2)
v2=$(grep -m1 -o '"variance_m2": [0-9.e-]*' "$tmp/merged.json" | cut -d' ' -f2)
check "variance halved ($v1 -> $v2)" awk -v a="$v1" -v b="$v2" 'BEGIN { exit !(b > 0 && (a / b - 2) ^ 2 < 1e-9) }'
check "the merged corrected map equals the map" cmp -s "$tmp/ais.json" "$tmp/merged-map.json"
expect 0 '"discrepancies": 0' -- "$sp" merge-measurements --map "$ais" \
  "$tmp/fixed.measurements.json" -o "$tmp/one.json" --json

# A file of another map: an error naming the file and the fingerprint, exit 1.
python3 - "$ais" "$tmp/other.json" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
m["manholes"][0]["diameter_m"] = m["manholes"][0]["diameter_m"] + 0.1
json.dump(m, open(sys.argv[2], "w"))
PY
expect 1 "fixed.measurements.json:\\\$.map.fingerprint: .*not of map" -- "$sp" merge-measurements \
  --map "$tmp/other.json" "$tmp/fixed.measurements.json" -o "$tmp/x.json"
# A bad file: the JSON path of the problem.
sed 's/"variance_m2": [0-9.e-]*/"variance_m2": -1/' "$tmp/fixed.measurements.json" >"$tmp/bad.json"
expect 1 "bad.json:\\\$.pipes\[0\].variance_m2" -- "$sp" merge-measurements --map "$ais" \
  "$tmp/bad.json" -o "$tmp/x.json"
expect 3 "missing.json" -- "$sp" merge-measurements --map "$ais" "$tmp/missing.json" -o "$tmp/x.json"
expect 2 "required" -- "$sp" merge-measurements --map "$ais" "$tmp/one.json"

# The discrepancies as a GeoJSON layer for GIS (with the GIS module).
if "$sp" --help | grep -q export-geojson; then
  expect 0 "wrote" -- "$sp" export-geojson --map "$ais" --crs EPSG:25832 \
    --measurements "$src/fuzz/corpus/measurements_json/observations.json" -o "$tmp/d.geojson"
  check "two discrepancy features" test "$(grep -c '"layer": "discrepancy"' "$tmp/d.geojson")" -eq 2
fi

# A map read from ISYBAU XML: the corrected map also as ISYBAU XML (OUT.xml; an .xml OUT names it
# and the JSON map goes to OUT.json), the source with the measured length changed in place and
# everything else as it was; merge-measurements writes it too; an .xml OUT for a map that is not
# ISYBAU is a usage error before the mission.
street=$src/datasets/isybau/street-2017.xml
cat >"$tmp/street-mission.json" <<'JSON'
{"format": "sewerplan-mission", "version": 1, "name": "street-check", "profile": "makro-plus",
 "start": {"manhole": "S1"},
 "tasks": [{"name": "in", "type": "inspect_pipe", "pipe": "S1"},
           {"name": "end", "type": "go_to", "at": {"manhole": "S1"}, "final": true}]}
JSON
expect 0 "corrected ISYBAU .*/street-fixed.xml: 1 lengths, 0 positions" -- "$sp" simulate \
  --map "$street" --mission "$tmp/street-mission.json" -q --world-errors lengths=1,length_rel=0.2 \
  --world-seed 3 --corrected-map "$tmp/street-fixed.xml"
check "the JSON map beside the ISYBAU copy" test -s "$tmp/street-fixed.json" \
  -a -s "$tmp/street-fixed.discrepancies.json" -a -s "$tmp/street-fixed.measurements.json"
# Only the Laenge of S1 and our comments differ from the source.
check "the ISYBAU copy is the source but for S1's Laenge" test "$(diff "$street" \
  "$tmp/street-fixed.xml" | grep '^[<>]' | grep -vc '<!-- sewerplan: ')" -eq 2
check "S1's measured length in its Laenge" grep -qE '<Laenge>2[0-9]\.[0-9]{2}</Laenge>' \
  "$tmp/street-fixed.xml"
expect 0 "pipes +4 " -- "$sp" info --map "$tmp/street-fixed.xml"
expect 0 "corrected ISYBAU .*/merged-street.xml: 1 lengths" -- "$sp" merge-measurements \
  --map "$street" "$tmp/street-fixed.measurements.json" -o "$tmp/m.json" \
  --corrected-map "$tmp/merged-street.json"
check "merge-measurements' ISYBAU copy is simulate's" cmp -s "$tmp/street-fixed.xml" \
  "$tmp/merged-street.xml"
expect 2 "ISYBAU XML is written only for a map read from ISYBAU XML" -- "$sp" simulate \
  --map "$ais" --mission "$mission" -q --corrected-map "$tmp/ais-fixed.xml"
check "nothing written for the refused name" test ! -e "$tmp/ais-fixed.json"

# The corrected map is written as JSON (.json, or no extension) or also as ISYBAU XML (.xml): any
# other name is refused before the mission (it wrote JSON into fixed.sewer).
expect 2 "--corrected-map $tmp/fixed.sewer: unknown extension \".sewer\" \(.json or .xml\)" -- \
  "$sp" simulate --map "$ais" --mission "$mission" -q --corrected-map "$tmp/fixed.sewer"
expect 2 "--corrected-map $tmp/fixed.txt: unknown extension" -- \
  "$sp" merge-measurements --map "$ais" "$tmp/one.json" -o "$tmp/z.json" --corrected-map "$tmp/fixed.txt"
expect 0 '' -- test ! -e "$tmp/fixed.sewer" -a ! -e "$tmp/fixed.txt" -a ! -e "$tmp/z.json"
# Failed writes: exit 3 naming the file.
expect 3 "/dev/full" -- "$sp" merge-measurements --map "$ais" "$tmp/one.json" -o /dev/full
expect 3 "/dev/full" -- "$sp" merge-measurements --map "$ais" "$tmp/one.json" -o "$tmp/y.json" \
  --corrected-map /dev/full
expect 3 "/dev/full" -- "$sp" simulate --map "$ais" --mission "$mission" -q --corrected-map /dev/full
expect 3 "$tmp/a-file/x.json" -- bash -c "echo x > '$tmp/a-file'; '$sp' simulate --map '$ais' \
  --mission '$mission' -q --corrected-map '$tmp/a-file/x.json'"

echo "measurements: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
