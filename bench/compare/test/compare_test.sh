#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# bench/compare's handling of external planners, with stand-ins for FF and Fast Downward: a plan
# printed as FF prints it (valid on the AIS instance, invalid on a generated one), a planner that
# runs past the time limit, and one that crashes. Usage: compare_test.sh PATH_TO_SEWERPLAN_COMPARE
# SOURCE_DIR
set -uo pipefail
compare=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0

check() {  # check PATTERN FILE WHAT
  if ! grep -qE -- "$1" "$2"; then
    echo "FAIL: $3: /$1/ not in $2:"
    cat "$2"
    failures=$((failures + 1))
  fi
}

# FF stand-in: the paper's corrected plan, in FF's output format.
{
  echo '#!/bin/sh'
  echo 'echo "ff: parsing domain file"; echo; echo "ff: found legal plan as follows"; echo'
  n=0
  while read -r line; do
    case "$line" in ''|'#'*|';'*) continue ;; esac
    echo "echo '        $n: $line'"
    n=$((n + 1))
  done < "$src/datasets/ais-testbed/plans/paper-corrected.plan"
} > "$tmp/ff"
printf '#!/bin/sh\nsleep 30\n' > "$tmp/slow"
printf '#!/bin/sh\nkill -SEGV $$\n' > "$tmp/crash"
chmod +x "$tmp/ff" "$tmp/slow" "$tmp/crash"

"$compare" --ff "$tmp/ff" --fd "$tmp/slow" --sizes 10 --tasks 3 --seeds 1 --time-limit 2 \
  --out "$tmp/out" 2> "$tmp/progress"
csv=$tmp/out/results.csv
check '^ais-testbed-paper,12,3,sewerplan,solved,[0-9.e-]+,[0-9.e-]+,585\.378' "$csv" "sewerplan on AIS"
check '^ais-testbed-paper,12,3,ff,solved,.*,585\.378[0-9]*,14,' "$csv" "FF's plan read back and costed"
check '^ais-testbed-paper,12,3,fd lama-first,timeout,' "$csv" "a planner past the limit"
check '^g10-t3-s1,10,3,ff,(invalid plan|unreadable plan),' "$csv" "a wrong plan is not counted as solved"
check '\[1/2\] ais-testbed-paper: sewerplan solved' "$tmp/progress" "a progress line"
check '^\| ais-testbed-paper \| 12 \| 3 \| solved' "$tmp/out/results.md" "the Markdown table"

"$compare" --ff "$tmp/crash" --no-datasets --sizes 10 --tasks 3 --seeds 1 --time-limit 5 \
  --out "$tmp/out2" 2> /dev/null
check '^g10-t3-s1,10,3,ff,crashed,.*signal 11' "$tmp/out2/results.csv" "a crash"

# A sewerplan run without a plan is labelled by what the planner said (its error code and message),
# not by its exit code: the paper's mission with 95 % of the battery held back is proven impossible
# ("no plan", with the planner's reason).
sed 's/"battery_reserve": 0.2/"battery_reserve": 0.95/' \
  "$src/datasets/ais-testbed/missions/paper.json" > "$tmp/tight.json"
# (One small generated instance beside it: without --sizes the default sweep runs 45 generated
# instances up to 100,000 manholes, two minutes that check nothing here.)
"$compare" --dataset "$src/datasets/ais-testbed/map.json:$tmp/tight.json" --time-limit 5 \
  --sizes 10 --tasks 3 --seeds 1 --out "$tmp/out3" 2> /dev/null
check '^[^,]*tight[^,]*,12,3,sewerplan,no plan,.*no-plan: the mission cannot be completed: .*no plan does all 3' \
  "$tmp/out3/results.csv" "a proven no plan, in the planner's words"

# Issue 30: every write checked. A results file on a full disk (/dev/full) is exit 3 naming it, the
# CSV written row by row as much as the Markdown table at the end; so is an output directory that
# cannot be made.
for file in results.csv results.md; do
  mkdir -p "$tmp/full-$file/instances"
  ln -s /dev/full "$tmp/full-$file/$file"
  "$compare" --no-datasets --sizes 10 --tasks 3 --seeds 1 --time-limit 5 \
    --out "$tmp/full-$file" > /dev/null 2> "$tmp/full-$file.err"
  code=$?
  if [ "$code" -ne 3 ]; then
    echo "FAIL: $file on a full disk: exit $code, not 3"
    failures=$((failures + 1))
  fi
  check "cannot write $tmp/full-$file/$file: No space left on device" "$tmp/full-$file.err" \
    "$file on a full disk named"
done
"$compare" --no-datasets --sizes 10 --tasks 3 --seeds 1 --out /dev/full/out > /dev/null \
  2> "$tmp/nodir.err"
code=$?
[ "$code" -eq 3 ] || { echo "FAIL: an output directory under a device: exit $code, not 3"; failures=$((failures + 1)); }
check 'cannot write /dev/full/out/instances' "$tmp/nodir.err" "the directory that cannot be made"

[ "$failures" -eq 0 ] && echo "compare: all checks passed"
[ "$failures" -eq 0 ]
