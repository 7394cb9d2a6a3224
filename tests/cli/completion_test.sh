#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The bash completion (`sewerplan completion`, apps/sewerplan/cmd_completion.cc) offers exactly
# what the command accepts: its commands are `sewerplan --help`'s, and for every command and every
# command's command (campaign merge, motion precompute) its options are exactly those of that
# command's --help (the options CLI11 parses with), no more (the scraped completion offered
# `plan --can`, `sim-node --json`, from the text under every --help) and no fewer. It also
# completes commands, options and their values, and files.
# Usage: completion_test.sh PATH_TO_SEWERPLAN SOURCE_DIR [SCRIPT] (SCRIPT: another completion
# script to check instead of the command's own, such as an older one)
set -euo pipefail
sp=$1
src=$2
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
if [ -n "${3:-}" ]; then
  # shellcheck source=/dev/null
  source "$3"
else
  # shellcheck source=/dev/null
  source <("$sp" completion)
fi
subcommands() { awk '/^Subcommands:/ {on = 1; next} on && !NF {exit} on && /^  [a-z]/ {print $1}'; }
help_commands=$(subcommands <<<"$("$sp" --help)" | sort | tr '\n' ' ')
script_commands=$(tr ' ' '\n' <<<"$_sewerplan_commands" | sort | tr '\n' ' ')
[ "$help_commands" = "$script_commands" ] ||
  fail "the completion's commands differ from sewerplan --help's"$'\n'"  --help:     $help_commands"$'\n'"  completion: $script_commands"
complete_words() {  # complete_words WORD...: COMPREPLY for the last word, in `got` (one line)
  COMP_WORDS=("$@")
  COMP_CWORD=$(($# - 1))
  COMPREPLY=()
  _sewerplan || true  # as bash runs it: without errexit (compgen fails on no match)
  got="${COMPREPLY[*]}"
}
same_words() {  # same_words A B: the same words, in any order
  local -A seen=()
  local a=($1) b=($2) w
  [ "${#a[@]}" -eq "${#b[@]}" ] || return 1
  for w in "${a[@]}"; do seen[$w]=1; done
  for w in "${b[@]}"; do [ -n "${seen[$w]:-}" ] || return 1; done
}
# The options in a --help's Options section: "  -a,--algorithm TEXT=auto  ..." gives -a --algorithm.
help_options() { awk '/^Options:/ {on = 1; next} on && !NF {exit} on && /^  -/ {gsub(",", " ", $1); print $1}'; }
count=0
check_options() {  # check_options HELP WORD...: the command WORD...'s completion against HELP
  local help=$1 want
  shift
  want=$(help_options <<<"$help")
  complete_words "$sp" "$@" -
  same_words "$got" "$want" ||
    fail "'sewerplan $* -' completes to"$'\n'"  $got"$'\n'"not to its --help's options"$'\n'"  $want"
  count=$((count + 1))
}
for c in $(subcommands <<<"$("$sp" --help)"); do
  help=$("$sp" "$c" --help)
  check_options "$help" "$c"
  for s in $(subcommands <<<"$help"); do check_options "$("$sp" "$c" "$s" --help)" "$c" "$s"; done
done
[ "$count" -ge 18 ] || fail "only $count commands checked"

expect_completion() {  # expect_completion WANT WORD...
  local want=$1
  shift
  complete_words "$sp" "$@"
  same_words "$got" "$want" || fail "'sewerplan ${*}' completes to '$got', not '$want'"
}
expect_completion plan pl
expect_completion "--map --max-strand-risk" plan --ma
expect_completion "" plan --ca           # simulate's --can, not plan's
expect_completion "" sim-node --js       # sim-node prints no JSON
expect_completion astar plan -a as
# Option values from the tables the parsers read (algorithms, heuristics, topologies).
expect_completion "max" plan --heuristic ma
expect_completion "meshed" generate --topology me
expect_completion --json simulate --js
expect_completion merge campaign me      # a command's command
expect_completion precompute motion pre
expect_completion "--quiet" campaign merge "$src" --qu
expect_completion "--iterations" motion precompute --map x.json --it
expect_completion "--version" --vers
# --gis-fields on every command that reads a map, and a JSON file (or a directory) after it.
for command in validate info convert plan check export-pddl import-plan simulate sim-node campaign render serve; do
  expect_completion --gis-fields "$command" --gis-f
done
got=$(cd "$src/datasets/ais-testbed" && complete_words "$sp" info --gis-fields ma && echo "$got")
[ "$got" = "map.json" ] || fail "'info --gis-fields ma' completes to '$got', not 'map.json'"
echo "completion: $count commands' options; $failures failed"
[ "$failures" -eq 0 ]
