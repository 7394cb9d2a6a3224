#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# A run that needs no module loads nothing beyond the C and C++ runtimes, simdjson and pugixml
# (docs/modules.md): every heavy dependency (GDAL, PROJ, OMPL, cairo, httplib and OpenSSL) sits
# behind a module, and this keeps a new one from creeping back into the command's links. The
# commands a script calls most: --version, validate, info, plan, check, export-pddl,
# generate and convert; the set of files each one loads (the dynamic loader's trace, LD_DEBUG=files)
# must be within the list below (and a sanitizer's runtime, in those builds).
# Usage: lean_start_test.sh PATH_TO_SEWERPLAN SOURCE_DIR
set -euo pipefail
sp=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
data=$src/datasets/ais-testbed
allowed='^(libsimdjson\.so\.[0-9]+|libpugixml\.so\.[0-9]+|libstdc\+\+\.so\.6|libm\.so\.6|libgcc_s\.so\.1|libc\.so\.6|lib(asan|ubsan|tsan|clang_rt)[^ ]*)$'

source "$(dirname "$0")/loader_trace.sh"

# files NAME COMMAND...: the files COMMAND loads, one a line, into $tmp/NAME.files.
files() {
  local name=$1
  shift
  loaded "$tmp/$name.trace" "$@"
  sed -n 's/.*file=\([^ ]*\) \[.*/\1/p' "$tmp/$name.trace" | sort -u > "$tmp/$name.files"
  grep -q '^libc\.so' "$tmp/$name.files" || { echo "FAIL: no loader trace for $name"; exit 1; }
}

"$sp" plan --map "$data/map.json" --mission "$data/missions/paper.json" -q -o "$tmp/paper.plan"
files version "$sp" --version
files validate "$sp" validate --map "$data/map.json"
files info "$sp" info --map "$data/map.json"
files plan "$sp" plan --map "$data/map.json" --mission "$data/missions/paper.json" -q
files check "$sp" check --map "$data/map.json" --mission "$data/missions/paper.json" \
  "$tmp/paper.plan"
files export "$sp" export-pddl --map "$data/map.json" --mission "$data/missions/paper.json" \
  --out "$tmp/pddl"
files generate "$sp" generate --manholes 30 --seed 1 -o "$tmp/g.json"
files convert "$sp" convert --map "$data/map.json" -o "$tmp/map.sewer"
status=0
for f in "$tmp"/*.files; do
  name=$(basename "$f" .files)
  if grep -Ev "$allowed" "$f" > "$tmp/$name.extra"; then
    echo "FAIL: sewerplan $name loaded more than it needs:"
    cat "$tmp/$name.extra"
    status=1
  fi
done
[ "$status" -eq 0 ] && echo "lean start: ok"
exit "$status"
