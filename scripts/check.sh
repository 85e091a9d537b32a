#!/usr/bin/env bash
# make check: the long runs make test leaves out, each into WS/check_results, ending with one
# line "N passed, N failed" (non-zero exit when any failed or none ran):
#  - the soak: 10 million steps at rest and of random tilting, and an hour of simulated time of a
#    session played and called at random;
#  - every core test, the runner with its command-line tests and the ROS layer's unit tests under
#    the sanitizers;
#  - the fuzzers for FUZZ_SECONDS each (default 120, side by side);
#  - the whole speed-accuracy sweep, checked (into WS/check_results, not doc/);
#  - the long cases of record and replay.
set -uo pipefail
export PATH="/usr/bin:$PATH"
# shellcheck source=scripts/workspace.sh
. "$(dirname "$0")/workspace.sh"
use_workspace
export ROS_HOME="${ROS_HOME:-$WS/ros_home}"
results=$WS/check_results
rm -rf "$results"
mkdir -p "$results"
failed=()
bin=$WS/devel/lib/marble_maze
(cd "$WS" && catkin_make -j2 tests) > "$WS/check_build.log" 2>&1 ||
  { tail -n 20 "$WS/check_build.log"; failed+=(--also-failed "the tests' build"); }

echo "soak (about 10 s)"
MARBLE_MAZE_SOAK_STEPS=10000000 MARBLE_MAZE_SOAK_SECONDS=3600 "$bin/test_core" \
  --gtest_filter='Soak.*' --gtest_output="xml:$results/gtest-soak.xml" > "$results/soak.log" 2>&1 ||
  grep -E "FAILED|Failure" "$results/soak.log"

echo "the sanitized tests (about 5 minutes)"
bash "$repo/scripts/sanitize.sh" full "$results" || failed+=(--also-failed "sanitized tests")

seconds=${FUZZ_SECONDS:-120}
echo "the fuzzers, $seconds s each"
bash "$repo/scripts/fuzz.sh" "$seconds" "$results" || failed+=(--also-failed "fuzzers")

echo "the speed-accuracy sweep (about a minute)"
if "$bin/marble_maze_tradeoff" --out "$results/tradeoff.csv" > "$results/tradeoff.log" 2>&1; then
  MARBLE_MAZE_TRADEOFF_CSV="$results/tradeoff.csv" "$bin/test_tradeoff_cli" \
    --gtest_filter='*FullSweep*' --gtest_output="xml:$results/gtest-tradeoff_sweep.xml" \
    > "$results/tradeoff_check.log" 2>&1 || grep -E "Failure|FAILED" "$results/tradeoff_check.log"
else
  tail -n 5 "$results/tradeoff.log"
  failed+=(--also-failed "the speed-accuracy sweep")
fi

echo "record and replay, the long cases (about 3 minutes)"
MARBLE_MAZE_TESTS=long MARBLE_MAZE_WS="$WS" /usr/bin/python3 "$repo/test/ros/test_record_replay.py" \
  --gtest_output="xml:$results/pyunit-record_replay_long.xml" > "$results/record_replay.log" 2>&1 ||
  tail -n 20 "$results/record_replay.log"

/usr/bin/python3 "$repo/scripts/count_results.py" "$results" "${failed[@]}"
