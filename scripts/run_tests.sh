#!/usr/bin/env bash
# Runs every gtest and rostest case and ends with one line "N passed, N failed".
# Exits non-zero when any failed or none ran.
set -uo pipefail
export PATH="/usr/bin:$PATH"
. "$(dirname "$0")/workspace.sh"
results=$WS/build/test_results
rm -rf "$results"
(cd "$WS" && catkin_make run_tests -j2) > "$WS/run_tests.log" 2>&1
status=$?
extra=()
if [ $status -ne 0 ]; then
  tail -n 40 "$WS/run_tests.log"
  echo "catkin_make run_tests failed (exit $status); the whole log is $WS/run_tests.log"
  extra=(--also-failed "catkin_make run_tests")
fi
# The core's tests again under the sanitizers, into the same results.
if ! bash "$repo/scripts/sanitize.sh" "$results/marble_maze"; then
  echo "the sanitized core tests failed (logs in $WS/sanitize)"
  extra+=(--also-failed "sanitized core tests")
fi
# The fuzzers, half a minute each (make fuzz runs them longer), into the same results.
if ! bash "$repo/scripts/fuzz.sh" 30 "$results/marble_maze"; then
  echo "the fuzzers found something or failed to build (logs in $WS/fuzz)"
  extra+=(--also-failed "fuzzers")
fi
# Every benchmark case's instructions a step against its budget (make budgets, about 30 s): one
# result a rule of bench/instruction_budgets.txt.
if ! bash "$repo/scripts/check_budgets.sh" "$results/marble_maze" > "$WS/budgets.log" 2>&1; then
  grep -iE "failed|error" "$WS/budgets.log" || tail -n 20 "$WS/budgets.log"
  echo "instruction budgets: see $WS/budgets.log"
  # (A count or a budgets file that could not be read leaves no result to fail.)
  [ -f "$results/marble_maze/instruction_budgets.xml" ] ||
    extra+=(--also-failed "instruction budgets (no result: see $WS/budgets.log)")
fi
# catkin_make run_tests exits 0 even when tests fail: the verdict comes from the result files.
/usr/bin/python3 "$repo/scripts/count_results.py" "$results" "${extra[@]}"
