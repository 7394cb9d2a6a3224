#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# `serve`'s address and connections: with --host ::1 (or [::1]) the printed URL is
# http://[::1]:PORT/, an address a browser and curl open (it was http://::1:PORT/, which none does);
# --max-connections N serves N connections at once and the rest wait their turn: with N = 2 and
# two connections open that send nothing, a request waits (until one of them is closed), and is
# answered once they are; --max-connections 0 is a usage error.
# Usage: serve_address_test.sh PATH_TO_SEWERPLAN SOURCE_DIR
set -euo pipefail
sp=$1
src=$2
tmp=$(mktemp -d)
pid=
stop() {
  if [ -n "$pid" ]; then kill "$pid" 2> /dev/null || true; wait "$pid" 2> /dev/null || true; fi
  pid=
}
trap 'stop; rm -rf "$tmp"' EXIT
map=$src/datasets/ais-testbed/map.json

# Starts serve with "$@", waits for its address in $url (pattern $1 first).
start() {
  local pattern=$1
  shift
  "$sp" serve --map "$map" --port 0 "$@" > "$tmp/serve.log" 2>&1 &
  pid=$!
  url=
  for _ in $(seq 1 300); do
    url=$(grep -oE "$pattern" "$tmp/serve.log" 2> /dev/null | head -1 || true)
    [ -n "$url" ] && return 0
    if ! kill -0 "$pid" 2> /dev/null; then
      wait "$pid" && code=0 || code=$?
      pid=
      return "$code"
    fi
    sleep 0.05
  done
  cat "$tmp/serve.log"
  echo "FAIL: serve $* printed no address"
  exit 1
}

# IPv6 loopback, if this machine has it (serve exits 3 when it cannot listen: then skipped).
for host in ::1 '[::1]'; do
  if start 'http://\S+' --host "$host"; then
    [[ $url =~ ^http://\[::1\]:[0-9]+/$ ]] || { echo "FAIL: --host $host printed $url"; exit 1; }
    curl -sfg "${url}api/maps" | jq -e '.maps[0].id == "map"' > /dev/null || {
      echo "FAIL: $url does not answer"; exit 1; }
    grep -q warning "$tmp/serve.log" && { echo "FAIL: --host $host warned:"; cat "$tmp/serve.log"; exit 1; }
    stop
  else
    code=$?
    [ "$code" = 3 ] || { cat "$tmp/serve.log"; echo "FAIL: serve --host $host exited $code"; exit 1; }
    echo "no IPv6 loopback here: --host $host not checked"
    v6_missing=1
  fi
done

# --max-connections: two idle connections hold both workers; a request waits, then is answered.
start 'http://127\.0\.0\.1:[0-9]+/' --max-connections 2
port=${url##*:}
port=${port%/}
exec 3<> "/dev/tcp/127.0.0.1/$port" 4<> "/dev/tcp/127.0.0.1/$port"
sleep 0.1  # both accepted and on their workers
if curl -sf --max-time 0.5 "${url}api/maps" > /dev/null; then
  echo "FAIL: --max-connections 2 answered a third connection while two were open"
  exit 1
fi
exec 3>&- 4>&-
curl -sf --max-time 10 "${url}api/maps" | jq -e '.maps | length == 1' > /dev/null || {
  echo "FAIL: no answer once the two connections were closed"; exit 1; }
stop

if "$sp" serve --map "$map" --port 0 --max-connections 0 > "$tmp/zero.log" 2>&1; then
  echo "FAIL: --max-connections 0 was taken"; exit 1
else
  code=$?
  [ "$code" = 2 ] && grep -q 'max-connections' "$tmp/zero.log" || {
    cat "$tmp/zero.log"; echo "FAIL: --max-connections 0 exited $code"; exit 1; }
fi
echo "serve's address and connections: ok${v6_missing:+ (no IPv6 here)}"
