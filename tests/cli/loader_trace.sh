# SPDX-License-Identifier: MIT
# Sourced by the CLI's lazy-loading tests (lazy_*_test.sh, lean_start_test.sh): what a command loads,
# in the dynamic loader's own trace.
#
# loaded OUT COMMAND...: run COMMAND (its standard output dropped) under LD_DEBUG=files, its trace
# to the file OUT.
loaded() {
  local out=$1
  shift
  LD_DEBUG=files LD_DEBUG_OUTPUT="$out" "$@" > /dev/null
  cat "$out".* > "$out" && rm -f "$out".*
}
