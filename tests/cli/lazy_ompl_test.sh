#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# OMPL is loaded only by the runs that plan a manhole motion, through the OMPL module
# (sewerplan/modules/ompl_table.h): `--version`, `validate`, and `plan` with or without a motion table
# never load OMPL, Boost.Serialization or ODE (the dynamic loader's own trace, LD_DEBUG=files);
# `motion precompute` does, and writes its table. A sewerplan whose module is missing (the
# executable copied alone), or is not a sewerplan module, still plans, and its motion precompute is
# an error naming the module and why (exit 1, no crash).
# Usage: lazy_ompl_test.sh PATH_TO_SEWERPLAN SOURCE_DIR
set -euo pipefail
sp=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
data=$src/datasets/ais-testbed
mkdir -p "$tmp/motion"
cp "$data/map.json" "$tmp/motion/map.json"
plan=(plan --map "$data/map.json" --mission "$data/missions/paper.json" -q)
heavy='file=.*(libompl|libboost_serialization|libode|libccd|sewerplan_ompl)'

source "$(dirname "$0")/loader_trace.sh"  # loaded OUT COMMAND...

loaded "$tmp/precompute.trace" "$sp" motion precompute --map "$tmp/motion/map.json" -q
grep -q 'file=.*sewerplan_ompl\.so' "$tmp/precompute.trace" || {
  echo "FAIL: motion precompute did not load the OMPL module"; exit 1; }
grep -q 'file=.*libompl' "$tmp/precompute.trace" || { echo "FAIL: motion precompute did not load OMPL"; exit 1; }
grep -q '"passages"' "$tmp/motion/map.motion.json" || { echo "FAIL: no motion table written"; exit 1; }

for run in version plan validate motion_plan; do
  case $run in
    version) args=(--version) ;;
    plan) args=("${plan[@]}") ;;
    validate) args=(validate --map "$data/map.json") ;;
    # The table beside the map is used, not planned: still no OMPL.
    motion_plan) args=(plan --map "$tmp/motion/map.json" --mission "$data/missions/paper.json") ;;
  esac
  loaded "$tmp/$run.trace" "$sp" "${args[@]}" 2> "$tmp/$run.err"
  grep -q 'file=libc\.so' "$tmp/$run.trace" || { echo "FAIL: no loader trace for $run"; exit 1; }
  if grep -Eq "$heavy" "$tmp/$run.trace"; then
    echo "FAIL: sewerplan $run loaded OMPL or its module:"
    grep -E "$heavy" "$tmp/$run.trace" | head -5
    exit 1
  fi
done
grep -q 'motion: using 50 planned manhole passages' "$tmp/motion_plan.err" || {
  echo "FAIL: plan did not use the motion table:"; cat "$tmp/motion_plan.err"; exit 1; }

# The executable alone, without its lib/sewerplan/sewerplan_ompl.so.
mkdir -p "$tmp/alone/bin"
cp "$sp" "$tmp/alone/bin/sewerplan"
"$tmp/alone/bin/sewerplan" "${plan[@]}" > "$tmp/alone.plan"
cmp -s "$tmp/alone.plan" <("$sp" "${plan[@]}") || { echo "FAIL: the plan differs without the module"; exit 1; }
# precompute_fails NAME PATTERN [ENV...]: motion precompute of the alone copy exits 1 with PATTERN.
precompute_fails() {
  local name=$1 pattern=$2 status=0
  shift 2
  env "$@" "$tmp/alone/bin/sewerplan" motion precompute --map "$tmp/motion/map.json" \
    -o "$tmp/$name.motion.json" 2> "$tmp/$name.err" > /dev/null || status=$?
  [ "$status" -eq 1 ] || { echo "FAIL: motion precompute ($name) exited $status, want 1"; cat "$tmp/$name.err"; exit 1; }
  grep -Eq "$pattern" "$tmp/$name.err" || { echo "FAIL: unclear error ($name):"; cat "$tmp/$name.err"; exit 1; }
  [ ! -e "$tmp/$name.motion.json" ] || { echo "FAIL: a table was written ($name)"; exit 1; }
}
need='motion precompute: sewerplan cannot plan manhole motions: they need OMPL, but the ompl module'
precompute_fails missing "$need is missing \(looked for .*/lib/sewerplan/sewerplan_ompl\.so.*\); the angle and step rules apply"
# Not a module: a file that does not load, and a shared library without the module's symbols.
mkdir -p "$tmp/garbage" "$tmp/foreign"
echo 'not an ELF file' > "$tmp/garbage/sewerplan_ompl.so"
precompute_fails garbage "$need .*/garbage/sewerplan_ompl\.so cannot be loaded: " SEWERPLAN_MODULE_DIR="$tmp/garbage"
cp "$(ldd "$sp" | awk '/libm\.so/ {print $3}')" "$tmp/foreign/sewerplan_ompl.so"
precompute_fails foreign "$need .*/foreign/sewerplan_ompl\.so has no ABI stamp \(sewerplan_ompl_module_stamp\)" \
  SEWERPLAN_MODULE_DIR="$tmp/foreign"
echo "lazy OMPL: ok"
