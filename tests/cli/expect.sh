# SPDX-License-Identifier: MIT
# What the CLI tests share: the counters, `expect`, `run_once` with `expect_ran`, and `check`, sourced
# by each test script:
#   source "$(dirname "${BASH_SOURCE[0]}")/expect.sh"
# Set expect_timeout (seconds) before a call to fail a command that hangs instead of waiting.
failures=0
passed=0
expect_timeout=${expect_timeout:-}

# expect CODE PATTERN -- COMMAND...: runs COMMAND, checks its exit code and that PATTERN (grep -E)
# occurs in its stdout+stderr.
expect() {
  local code=$1 pattern=$2
  shift 3
  run_once "$@"
  expect_ran "$code" "$pattern"
}

# run_once COMMAND...: runs COMMAND and keeps its exit code and stdout+stderr, for expect_ran to
# check more than one thing of one run (each sewerplan start costs 0.1 s and more under ASan).
run_once() {
  if [ -n "$expect_timeout" ]; then
    ran_out=$(timeout "$expect_timeout" "$@" 2>&1)
  else
    ran_out=$("$@" 2>&1)
  fi
  ran_code=$?
  ran_command="$*"
}

# expect_ran CODE PATTERN: the command run_once ran last exited with CODE and PATTERN (grep -E)
# occurs in its stdout+stderr.
expect_ran() {
  local code=$1 pattern=$2
  if [ "$ran_code" -ne "$code" ] || ! grep -qE -- "$pattern" <<<"$ran_out"; then
    echo "FAIL: $ran_command -> exit $ran_code (want $code), output:"
    echo "$ran_out" | head -20
    echo "(wanted /$pattern/)"
    failures=$((failures + 1))
  else
    passed=$((passed + 1))
  fi
}

# check DESCRIPTION COMMAND...: the command succeeds.
check() {
  local what=$1
  shift
  if "$@"; then passed=$((passed + 1)); else echo "FAIL: $what"; failures=$((failures + 1)); fi
}
