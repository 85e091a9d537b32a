#!/usr/bin/env bash
# make test: every gtest, unittest and rostest case, the core's tests again under the sanitizers,
# and the fuzzers for a few seconds each; ends with one line "N passed, N failed" and exits
# non-zero when any failed or none ran. (make check runs the long ones: scripts/check.sh.)
set -uo pipefail
export PATH="/usr/bin:$PATH"
# shellcheck source=scripts/workspace.sh
. "$(dirname "$0")/workspace.sh"
results=$WS/build/test_results
rm -rf "$results"
failed=()
echo "gtest, unittest and rostest (about 3 minutes; log: $WS/run_tests.log)"
(cd "$WS" && catkin_make run_tests -j2) > "$WS/run_tests.log" 2>&1
status=$?
if [ $status -ne 0 ]; then
  tail -n 40 "$WS/run_tests.log"
  echo "catkin_make run_tests failed (exit $status); the whole log is $WS/run_tests.log"
  failed+=(--also-failed "catkin_make run_tests")
fi
echo "the core's tests under the sanitizers (logs: $WS/sanitize)"
if ! bash "$repo/scripts/sanitize.sh" quick "$results/marble_maze"; then
  echo "the sanitized core tests failed (logs in $WS/sanitize)"
  failed+=(--also-failed "sanitized core tests")
fi
echo "the fuzzers, 10 s each"
if ! bash "$repo/scripts/fuzz.sh" 10 "$results/marble_maze"; then
  echo "the fuzzers found something or failed to build (logs in $WS/sanitize)"
  failed+=(--also-failed "fuzzers")
fi
# catkin_make run_tests exits 0 even when tests fail: the verdict comes from the result files.
/usr/bin/python3 "$repo/scripts/count_results.py" "$results" "${failed[@]}"
