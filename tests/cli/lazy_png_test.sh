#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# cairo is loaded only to draw a PNG, through the PNG module (sewerplan/modules/png_table.h):
# `--version`, `plan`, `validate` and `render` to SVG never load cairo or the module (the dynamic
# loader's own trace, LD_DEBUG=files); `render` to PNG does, and writes a PNG. A sewerplan whose
# module is missing (the executable copied alone), or whose module is not one (a file that is no
# shared object, another module's file under its name), still plans and draws SVG, and its PNG is
# an error naming the module and why, with the usage of a failed command (exit 1, no crash).
# Usage: lazy_png_test.sh PATH_TO_SEWERPLAN SOURCE_DIR [OTHER_MODULE]
set -euo pipefail
sp=$1
src=$2
other=${3:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
data=$src/datasets/ais-testbed
plan=(plan --map "$data/map.json" --mission "$data/missions/paper.json" -q)
render=(render --map "$data/map.json" --mission "$data/missions/paper.json")
cairo='file=.*(libcairo|sewerplan_png)'

source "$(dirname "$0")/loader_trace.sh"  # loaded OUT COMMAND...
for run in version plan validate svg; do
  case $run in
    version) args=(--version) ;;
    plan) args=("${plan[@]}") ;;
    validate) args=(validate --map "$data/map.json") ;;
    svg) args=("${render[@]}" -o "$tmp/map.svg") ;;
  esac
  loaded "$tmp/$run.trace" "$sp" "${args[@]}"
  grep -q 'file=libc\.so' "$tmp/$run.trace" || { echo "FAIL: no loader trace for $run"; exit 1; }
  if grep -Eq "$cairo" "$tmp/$run.trace"; then
    echo "FAIL: sewerplan $run loaded cairo or the PNG module:"
    grep -E "$cairo" "$tmp/$run.trace" | head -5
    exit 1
  fi
done
grep -q '<svg' "$tmp/map.svg" || { echo "FAIL: no SVG written"; exit 1; }

loaded "$tmp/png.trace" "$sp" "${render[@]}" -o "$tmp/map.png"
grep -q 'file=.*sewerplan_png\.so' "$tmp/png.trace" || {
  echo "FAIL: render to PNG did not load the PNG module"; exit 1; }
grep -q 'file=.*libcairo' "$tmp/png.trace" || { echo "FAIL: render to PNG did not load cairo"; exit 1; }
[ "$(head -c 8 "$tmp/map.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || {
  echo "FAIL: no PNG written"; exit 1; }

# png_fails NAME PATTERN [ENV...]: render to PNG with the executable alone (and ENV) exits 1, its
# error matching PATTERN, and writes nothing; plan and SVG still work.
png_fails() {
  local name=$1 pattern=$2
  shift 2
  env "$@" "$tmp/alone/bin/sewerplan" "${plan[@]}" > "$tmp/$name.plan"
  cmp -s "$tmp/$name.plan" <("$sp" "${plan[@]}") || { echo "FAIL ($name): the plan differs"; exit 1; }
  env "$@" "$tmp/alone/bin/sewerplan" "${render[@]}" -o "$tmp/$name.svg" > /dev/null
  cmp -s "$tmp/$name.svg" "$tmp/map.svg" || { echo "FAIL ($name): the SVG differs"; exit 1; }
  local status=0
  env "$@" "$tmp/alone/bin/sewerplan" "${render[@]}" -o "$tmp/$name.png" 2> "$tmp/$name.err" || status=$?
  [ "$status" -eq 1 ] || {
    echo "FAIL ($name): render to PNG exited $status, want 1"; cat "$tmp/$name.err"; exit 1; }
  grep -Eq "$pattern" "$tmp/$name.err" || { echo "FAIL ($name): unclear error:"; cat "$tmp/$name.err"; exit 1; }
  [ ! -e "$tmp/$name.png" ] || { echo "FAIL ($name): a PNG was written"; exit 1; }
}

# The executable alone, without its lib/sewerplan/sewerplan_png.so.
mkdir -p "$tmp/alone/bin"
cp "$sp" "$tmp/alone/bin/sewerplan"
png_fails missing \
  "a PNG picture needs cairo, but the png module is missing \(looked for .*/lib/sewerplan/sewerplan_png\.so"
# A file of that name that is no shared object: dlopen's reason.
mkdir -p "$tmp/notelf"
echo "not a module" > "$tmp/notelf/sewerplan_png.so"
png_fails notelf \
  "a PNG picture needs cairo, but the png module .*/notelf/sewerplan_png\.so cannot be loaded: .*" \
  SEWERPLAN_MODULE_DIR="$tmp/notelf"
# Another module's file under its name: a shared object without the PNG module's stamp.
if [ -n "$other" ]; then
  mkdir -p "$tmp/other"
  cp "$other" "$tmp/other/sewerplan_png.so"
  png_fails other \
    "a PNG picture needs cairo, but the png module .*/other/sewerplan_png\.so has no ABI stamp \(sewerplan_png_module_stamp\)" \
    SEWERPLAN_MODULE_DIR="$tmp/other"
fi
echo "lazy PNG: ok"
