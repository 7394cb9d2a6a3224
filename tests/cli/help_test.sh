#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Every command's --help is clean (apps/sewerplan/help_format.h): no CLI11 artefacts in its usage
# line or options (`[]` and `[(0x)]` for a hidden positional, `FLOAT:FLOAT in [...]`), no trailing
# blanks, and no line wider than the width asked for ($COLUMNS, 80 without it). With MAN_PAGE, the
# man page fits 80 columns too (MANWIDTH=80 man -l). Usage: help_test.sh SEWERPLAN [MAN_PAGE]
set -euo pipefail
sp=$1
man_page=${2:-}
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

check() {  # check WIDTH NAME TEXT: one awk for the artefacts, trailing blanks and the width
  local width=$1 name=$2 text=$3
  awk -v w="$width" -v name="$name" '
    /\[\]|\(0x\)|\[\(|(FLOAT|UINT|INT|TEXT):(FLOAT|UINT|INT|TEXT)([^A-Z]|$)/ { print "FAIL: " name ": a CLI11 artefact: " $0; bad = 1 }
    / +$/ { print "FAIL: " name ": trailing blanks: " $0; bad = 1 }
    length > w { print "FAIL: " name ": " length " columns, more than " w ": " $0; bad = 1 }
    END { exit bad }' <<<"${text//$sp/sewerplan}" || failures=$((failures + 1))
}
# Every command, and the commands of each command (campaign merge, motion precompute), from the
# Subcommands sections of the --help texts themselves; each at 80 columns (the main one without
# COLUMNS, the default).
subcommands() { awk '/^Subcommands:/ {on = 1; next} on && !NF {exit} on && /^  [a-z]/ {print $1}'; }
pending=("")
count=0
while [ "${#pending[@]}" -gt 0 ]; do
  c=${pending[0]}
  pending=("${pending[@]:1}")
  read -ra words <<<"$c"
  if [ -z "$c" ]; then help80=$(unset COLUMNS; "$sp" --help); else help80=$(COLUMNS=80 "$sp" "${words[@]}" --help); fi
  check 80 "sewerplan $c --help" "$help80"
  count=$((count + 1))
  for s in $(subcommands <<<"$help80"); do pending+=("${c:+$c }$s"); done
done
[ "$count" -ge 17 ] || fail "only $count commands found in --help"
# $COLUMNS is the width (the man page's texts are written at 73; it is checked whole below).
check 60 "sewerplan simulate --help (COLUMNS=60)" "$(COLUMNS=60 "$sp" simulate --help)"

if [ -n "$man_page" ]; then
  wide=$(MANWIDTH=80 man -l "$man_page" 2>&1 | awk 'length > 80')
  [ -z "$wide" ] || fail "the man page is wider than 80 columns:"$'\n'"$wide"
  # One section per command, no more (a wrapped description's word was taken for a command); help2man's
  # own (from "Subcommands:" and "Exit codes:") begin with a capital.
  sections=$(awk '/^\.SS [a-z][-a-z]*$/ {print $2}' "$man_page" | tr '\n' ' ')
  want=$(subcommands <<<"$("$sp" --help)" | tr '\n' ' ')
  [ "$sections" = "$want" ] ||
    fail "the man page's command sections are"$'\n'"  $sections"$'\n'"not --help's commands"$'\n'"  $want"
fi
echo "help: $count --help texts, $failures failed"
[ "$failures" -eq 0 ]
