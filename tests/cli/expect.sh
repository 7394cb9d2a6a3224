# SPDX-License-Identifier: MIT
# What the CLI tests share: the counters, `expect` and `check`, sourced by each test script:
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
  local out
  if [ -n "$expect_timeout" ]; then
    out=$(timeout "$expect_timeout" "$@" 2>&1)
  else
    out=$("$@" 2>&1)
  fi
  local got=$?
  if [ "$got" -ne "$code" ] || ! grep -qE -- "$pattern" <<<"$out"; then
    echo "FAIL: $* -> exit $got (want $code), output:"
    echo "$out" | head -20
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
