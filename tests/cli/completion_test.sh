#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The bash completion (apps/sewerplan/completion/sewerplan.bash) stays in step with the CLI: its
# command list is the one `sewerplan --help` prints, and it completes commands and each command's
# options (read from that command's --help). Usage: completion_test.sh PATH_TO_SEWERPLAN SOURCE_DIR
set -euo pipefail
sp=$1
src=$2
# shellcheck source=/dev/null
source "$src/apps/sewerplan/completion/sewerplan.bash"
help_commands=$("$sp" --help | awk '/^Subcommands:/ {on = 1; next} on && !NF {exit} on {print $1}' | sort | tr '\n' ' ')
script_commands=$(tr ' ' '\n' <<<"$_sewerplan_commands" | sort | tr '\n' ' ')
if [ "$help_commands" != "$script_commands" ]; then
  echo "FAIL: the completion's commands differ from sewerplan --help's"
  echo "  --help:     $help_commands"
  echo "  completion: $script_commands"
  exit 1
fi
complete_words() {  # complete_words WORD...: COMPREPLY for the last word
  COMP_WORDS=("$@")
  COMP_CWORD=$(($# - 1))
  COMPREPLY=()
  _sewerplan
  echo "${COMPREPLY[*]}"
}
got=$(complete_words "$sp" pl)
[ "$got" = "plan" ] || { echo "FAIL: 'sewerplan pl' completes to '$got', not 'plan'"; exit 1; }
got=$(complete_words "$sp" plan --ma)
[ "$got" = "--map" ] || { echo "FAIL: 'sewerplan plan --ma' completes to '$got', not '--map'"; exit 1; }
got=$(complete_words "$sp" plan -a as)
[ "$got" = "astar" ] || { echo "FAIL: 'sewerplan plan -a as' completes to '$got', not 'astar'"; exit 1; }
got=$(complete_words "$sp" simulate --js)
[ "$got" = "--json" ] || { echo "FAIL: 'sewerplan simulate --js' completes to '$got'"; exit 1; }
# --gis-fields on every command that reads a map, and a JSON file (or a directory) after it.
for command in validate info convert plan check export-pddl import-plan simulate sim-node campaign render serve; do
  got=$(complete_words "$sp" "$command" --gis-f)
  [ "$got" = "--gis-fields" ] || { echo "FAIL: 'sewerplan $command --gis-f' completes to '$got'"; exit 1; }
done
got=$(cd "$src/datasets/ais-testbed" && complete_words "$sp" info --gis-fields ma)
[ "$got" = "map.json" ] || { echo "FAIL: 'info --gis-fields ma' completes to '$got', not 'map.json'"; exit 1; }
echo "completion: ${help_commands}"
