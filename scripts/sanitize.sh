#!/usr/bin/env bash
# Tests under AddressSanitizer and UndefinedBehaviorSanitizer (scripts/sanitized_build.sh):
#   bash scripts/sanitize.sh quick|full [RESULTS_DIR]
# quick (make test): the core's tests, a shorter soak, and without the four that take most of
# the time under the sanitizers (make test runs them unsanitized). full (make check): every core
# test, the runner with its command-line tests and the ROS layer's unit tests.
# Writes a JUnit file a shard into RESULTS_DIR and exits non-zero on a build failure, a failed
# test or a sanitizer's finding.
set -uo pipefail
export PATH="/usr/bin:$PATH"
# shellcheck source=scripts/workspace.sh
. "$(dirname "$0")/workspace.sh"
mode=${1:-quick}
results=${2:-$WS/build/test_results/marble_maze}
build="$WS/sanitize"
mkdir -p "$results"
filter="*"
binaries=(test_core_sanitized)
if [ "$mode" = quick ]; then
  filter="-StepCost.TilesSweptPerStepAreBoundedAtEveryMazeSize"
  filter+=":Extremes.TiltsSnappingBetweenEightySixDegreesNeverLetTheMarbleOutOfAClosedRoom"
  filter+=":Autopilot.ReachesTheGoalWithCommandsUpTo80MsLate"
  filter+=":Autopilot.PlaysAsFastWithStatesUpTo60MsOld"
else
  binaries+=(test_simulate_cli_sanitized test_ros_layer_sanitized)
fi
bash "$repo/scripts/sanitized_build.sh" "${binaries[@]}" || exit 1
# Each binary's cases in two shards side by side (gtest's sharding), one a core.
run_shard() {  # run_shard BINARY SHARD
  GTEST_TOTAL_SHARDS=2 GTEST_SHARD_INDEX=$2 MARBLE_MAZE_SOAK_STEPS=100000 \
    ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    "$build/$1" --gtest_filter="$filter" --gtest_output="xml:$results/gtest-$1-$2.xml" \
    > "$build/$1-$2.log" 2>&1
}
status=0
for binary in "${binaries[@]}"; do
  run_shard "$binary" 0 &
  first=$!
  run_shard "$binary" 1 || status=1
  wait "$first" || status=1
  grep -hE "runtime error|ERROR: (Address|Leak)Sanitizer|FAILED" "$build/$binary"-[01].log |
    head -n 20
done
exit $status
