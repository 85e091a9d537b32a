#!/usr/bin/env bash
# make test: builds the workspace, then runs every gtest, unittest and rostest case, the core's
# tests again under the sanitizers, and the fuzzers for a few seconds each; ends with one line
# "N passed, N failed" and exits non-zero when any failed or none ran. (make check runs the long
# ones: scripts/check.sh.)
#
# The sanitized build, its tests and the fuzzers run beside catkin's build and tests at the idle
# scheduling class (chrt --idle): they take only the CPU the others leave, while the build links
# or the rostests wait on their nodes, so they neither slow those down nor wait for them.
set -uo pipefail
export PATH="/usr/bin:$PATH"
# shellcheck source=scripts/workspace.sh
. "$(dirname "$0")/workspace.sh"
results=$WS/build/test_results
sanitized_results=$WS/sanitize/results  # (catkin's run_tests empties $results as it starts)
rm -rf "$results" "$sanitized_results"
mkdir -p "$WS/sanitize"
failed=()
echo "the core's tests under the sanitizers and the fuzzers, 10 s each, beside the others" \
  "(logs: $WS/sanitize)"
sanitized_tests() {  # in the background: the idle class, which the builds and runs inherit
  chrt --idle -p 0 "$BASHPID" > /dev/null
  bash "$repo/scripts/sanitize.sh" quick "$sanitized_results" || return 1
  bash "$repo/scripts/fuzz.sh" 10 "$sanitized_results" || return 2
}
set -m  # (the job in a process group of its own, stopped whole if this script ends first)
sanitized_tests > "$WS/sanitize/run_tests.out" 2>&1 &
sanitized=$!
set +m
trap 'kill -- -"$sanitized" 2> /dev/null' EXIT
bash "$repo/scripts/build.sh" || exit 1
echo "gtest, unittest and rostest (about 5 minutes; log: $WS/run_tests.log)"
(cd "$WS" && catkin_make run_tests -j2) > "$WS/run_tests.log" 2>&1
status=$?
if [ $status -ne 0 ]; then
  tail -n 40 "$WS/run_tests.log"
  echo "catkin_make run_tests failed (exit $status); the whole log is $WS/run_tests.log"
  failed+=(--also-failed "catkin_make run_tests")
fi
wait "$sanitized"
status=$?
cat "$WS/sanitize/run_tests.out"
mkdir -p "$results/marble_maze"
cp "$sanitized_results"/*.xml "$results/marble_maze/" 2>/dev/null
if [ $status -eq 1 ]; then
  echo "the sanitized core tests failed (logs in $WS/sanitize)"
  failed+=(--also-failed "sanitized core tests")
elif [ $status -ne 0 ]; then
  echo "the fuzzers found something or failed to build (logs in $WS/sanitize)"
  failed+=(--also-failed "fuzzers")
fi
# catkin_make run_tests exits 0 even when tests fail: the verdict comes from the result files.
/usr/bin/python3 "$repo/scripts/count_results.py" "$results" "${failed[@]}"
