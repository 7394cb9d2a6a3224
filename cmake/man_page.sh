#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Writes sewerplan's man page with help2man: the main --help and --version, and a COMMANDS section
# with every command's own --help (one page listing them all), the exit codes and where the docs are.
# Usage: man_page.sh SEWERPLAN OUT.1
set -euo pipefail
sp=$1
out=$2
# Every --help laid out 73 columns wide (apps/sewerplan/help_format.h): the page indents the
# commands' texts by 7, and a man page must fit 80 (tests/cli/help_test.sh checks it).
export COLUMNS=73
include=$(mktemp)
trap 'rm -f "$include"' EXIT
{
  echo "[COMMANDS]"
  # The help is read whole before awk stops at the list's end: an awk that exits while the command
  # still writes kills it with SIGPIPE, which pipefail made a failed build now and then.
  main_help=$("$sp" --help)
  commands=$(awk '/^Subcommands:/ {on = 1; next} on && !NF {exit} on && /^  [a-z]/ {print $1}' \
    <<<"$main_help")
  for c in $commands; do
    echo ".SS $c"
    echo ".nf"
    # Each command's --help without the footer it shares with the main --help (printed once).
    "$sp" "$c" --help | sed -e '/^Give the map with --map/,$d' -e "s|$sp|sewerplan|g" \
      -e 's/\\/\\e/g' -e 's/^\./\\\&./'
    echo ".fi"
  done
  echo "[SEE ALSO]"
  echo "The command line in full, with every --json schema: /usr/share/doc/sewerplan/cli.md."
  echo "The formats: /usr/share/doc/sewerplan/formats/. Example data:"
  echo "/usr/share/sewerplan/datasets/ais-testbed."
} > "$include"
help2man --no-info --no-discard-stderr --section=1 \
  --name="planning and replanning for autonomous sewer-inspection robots" \
  --include="$include" --output="$out" "$sp"
