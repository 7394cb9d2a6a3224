#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The server module is loaded only by `serve` (sewerplan/modules/server_table.h): `--version`, `plan` and
# `validate` never load cpp-httplib, OpenSSL or brotli's encoder (the dynamic loader's own trace,
# LD_DEBUG=files); `serve` does, answers the API and stops on SIGTERM with exit 0. A sewerplan whose
# module is missing (the executable copied alone) still plans, and its `serve` is an error naming the
# missing module (exit 1, no crash, nothing listening), and so is a file there that is no module.
# Usage: lazy_server_test.sh PATH_TO_SEWERPLAN SOURCE_DIR
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
data=$src/datasets/ais-testbed
plan=(plan --map "$data/map.json" --mission "$data/missions/paper.json" -q)
heavy='file=.*(libcpp-httplib|libssl|libcrypto|libbrotlienc|sewerplan_server)'

source "$(dirname "$0")/loader_trace.sh"  # loaded OUT COMMAND...
for run in version plan validate; do
  case $run in
    version) args=(--version) ;;
    plan) args=("${plan[@]}") ;;
    validate) args=(validate --map "$data/map.json") ;;
  esac
  loaded "$tmp/$run.trace" "$sp" "${args[@]}"
  grep -q 'file=libc\.so' "$tmp/$run.trace" || { echo "FAIL: no loader trace for $run"; exit 1; }
  if grep -Eq "$heavy" "$tmp/$run.trace"; then
    echo "FAIL: sewerplan $run loaded httplib, OpenSSL, brotli or the server module:"
    grep -E "$heavy" "$tmp/$run.trace" | head -5
    exit 1
  fi
done

# serve: loads the module and httplib, answers, and stops on SIGTERM. A map with reader's warnings
# beside: serve prints them at the start, as every command (issue 32), and lists them with the map.
LD_DEBUG=files LD_DEBUG_OUTPUT="$tmp/serve.trace" \
  "$sp" serve --map "$data/map.json" --map "$src/datasets/isybau/street-2013.xml" --port 0 \
  > "$tmp/serve.log" 2>&1 &
pid=$!
url=
for _ in $(seq 1 600); do
  url=$(grep -oE 'http://127\.0\.0\.1:[0-9]+/' "$tmp/serve.log" 2> /dev/null | head -1 || true)
  [ -n "$url" ] && break
  kill -0 "$pid" 2> /dev/null || { cat "$tmp/serve.log"; echo "FAIL: serve exited"; exit 1; }
  sleep 0.1
done
[ -n "$url" ] || { cat "$tmp/serve.log"; echo "FAIL: serve printed no address"; exit 1; }
curl -sf "${url}api/maps" > "$tmp/maps.json"
[ "$(jq -r '.maps[0].id' "$tmp/maps.json")" = map ] || {
  echo "FAIL: /api/maps does not list the map:"; cat "$tmp/maps.json"; exit 1; }
grep -q 'street-2013.xml: warning: 4 manholes have no shaft size' "$tmp/serve.log" || {
  cat "$tmp/serve.log"; echo "FAIL: serve did not print the reader's warnings"; exit 1; }
jq -e '.maps[1].warnings | map(.message) | any(test("4 manholes have no shaft size"))' \
  "$tmp/maps.json" > /dev/null || {
  echo "FAIL: /api/maps does not list the reader's warnings:"; cat "$tmp/maps.json"; exit 1; }
kill -TERM "$pid"
status=0
wait "$pid" || status=$?
pid=
[ "$status" -eq 0 ] || { cat "$tmp/serve.log"; echo "FAIL: serve exited $status on SIGTERM, want 0"; exit 1; }
cat "$tmp/serve.trace".* > "$tmp/serve.trace"
grep -q 'file=.*sewerplan_server\.so' "$tmp/serve.trace" || {
  echo "FAIL: serve did not load the server module"; exit 1; }
grep -q 'file=.*libcpp-httplib' "$tmp/serve.trace" || { echo "FAIL: serve did not load httplib"; exit 1; }

# The executable alone, without its lib/sewerplan/sewerplan_server.so.
mkdir -p "$tmp/alone/bin"
cp "$sp" "$tmp/alone/bin/sewerplan"
"$tmp/alone/bin/sewerplan" "${plan[@]}" > "$tmp/alone.plan"
cmp -s "$tmp/alone.plan" <("$sp" "${plan[@]}") || { echo "FAIL: the plan differs without the module"; exit 1; }
status=0
"$tmp/alone/bin/sewerplan" serve --map "$data/map.json" --port 0 > "$tmp/alone.out" 2> "$tmp/alone.err" ||
  status=$?
[ "$status" -eq 1 ] || { echo "FAIL: serve without the module exited $status, want 1"; cat "$tmp/alone.err"; exit 1; }
grep -q "serve needs cpp-httplib and OpenSSL, but the server module is missing (looked for .*/lib/sewerplan/sewerplan_server.so" \
  "$tmp/alone.err" || { echo "FAIL: unclear error:"; cat "$tmp/alone.err"; exit 1; }
if grep -q 'http://' "$tmp/alone.out"; then echo "FAIL: serve without the module listened"; exit 1; fi
# A file there that is no module: an error naming it and the loader's reason, not a crash.
mkdir -p "$tmp/alone/lib/sewerplan"
echo "not a shared object" > "$tmp/alone/lib/sewerplan/sewerplan_server.so"
status=0
"$tmp/alone/bin/sewerplan" serve --map "$data/map.json" --port 0 > /dev/null 2> "$tmp/bad.err" || status=$?
[ "$status" -eq 1 ] || { echo "FAIL: serve with a bad module exited $status, want 1"; cat "$tmp/bad.err"; exit 1; }
grep -q "serve needs cpp-httplib and OpenSSL, but the server module .*/lib/sewerplan/sewerplan_server.so cannot be loaded: " \
  "$tmp/bad.err" || { echo "FAIL: unclear error:"; cat "$tmp/bad.err"; exit 1; }
echo "lazy server: ok"
