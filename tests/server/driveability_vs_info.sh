#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The station's driveability endpoint answers what `sewerplan info --profile --json` says, on a map
# with a motion table beside it (docs/operator-station.md): the same "driveability" object with
# the table, and with ?motion=0 the same as with --no-motion. The table must change the answer on
# this map (one passage the planner rejects), else the comparison would prove nothing.
#
#   driveability_vs_info.sh SEWERPLAN_BINARY SOURCE_DIR
set -euo pipefail
sp=$1
src=$2
tmp=$(mktemp -d)
pid=
cleanup() {
  if [ -n "$pid" ]; then kill "$pid" 2> /dev/null || true; wait "$pid" 2> /dev/null || true; fi
  rm -rf "$tmp"
}
trap cleanup EXIT

cp "$src/datasets/ais-testbed/map.json" "$tmp/map.json"
if ! out=$("$sp" motion precompute --map "$tmp/map.json" --seed 3 -q 2>&1); then
  if grep -q 'has no OMPL' <<< "$out"; then
    echo "skipped: this build has no OMPL (no motion table)"
    exit 77
  fi
  echo "$out"
  exit 1
fi

"$sp" serve --map "$tmp/map.json" --port 0 > "$tmp/serve.log" 2>&1 &
pid=$!
url=
for _ in $(seq 1 600); do
  url=$(grep -oE 'http://127\.0\.0\.1:[0-9]+/' "$tmp/serve.log" 2> /dev/null | head -1 || true)
  [ -n "$url" ] && break
  kill -0 "$pid" 2> /dev/null || { cat "$tmp/serve.log"; echo "FAIL: serve exited"; exit 1; }
  sleep 0.1
done
[ -n "$url" ] || { cat "$tmp/serve.log"; echo "FAIL: serve printed no address"; exit 1; }

failures=0
# $1: what; $2: info's options; $3: the endpoint's extra query; $4: motion_table expected.
compare() {
  "$sp" info --map "$tmp/map.json" --profile makro-1.1 --json $2 2> /dev/null |
    jq -S '.driveability' > "$tmp/info.json"
  curl -sf "${url}api/maps/map/driveability?profile=makro-1.1$3" > "$tmp/endpoint-raw.json"
  if [ "$(jq '.motion_table' "$tmp/endpoint-raw.json")" != "$4" ]; then
    echo "FAIL: $1: motion_table is $(jq '.motion_table' "$tmp/endpoint-raw.json"), want $4"
    failures=$((failures + 1))
  fi
  jq -S 'del(.motion_table)' "$tmp/endpoint-raw.json" > "$tmp/endpoint.json"
  if ! diff -u "$tmp/info.json" "$tmp/endpoint.json"; then
    echo "FAIL: $1: the endpoint differs from info --profile --json"
    failures=$((failures + 1))
  fi
  cp "$tmp/endpoint.json" "$tmp/$1.json"
}
compare with-table "" "" true
compare no-motion "--no-motion" "&motion=0" false
if cmp -s "$tmp/with-table.json" "$tmp/no-motion.json"; then
  echo "FAIL: the motion table changes nothing on this map: the comparison proves nothing"
  failures=$((failures + 1))
fi
jq -e '[.passages[] | select(.motion_reason)] | length > 0' "$tmp/with-table.json" > /dev/null ||
  { echo "FAIL: no passage rejected by the motion table"; failures=$((failures + 1)); }
[ "$failures" -eq 0 ] && echo "ok: the driveability endpoint is info --profile's, with and without the motion table"
exit "$failures"
