#!/usr/bin/env bash
# The core's tests, the runner (with its command-line tests) and the ROS layer's unit tests under
# AddressSanitizer and UndefinedBehaviorSanitizer, built beside the workspace's own build
# (WS/sanitize, against its generated messages) so that the normal build stays optimised:
#   bash scripts/sanitize.sh [RESULTS_DIR]
# writes its JUnit file into RESULTS_DIR (for make test's count) and exits non-zero on a build
# failure, a failed test or a sanitizer's finding.
set -uo pipefail
export PATH="/usr/bin:$PATH"
. "$(dirname "$0")/workspace.sh"
results=${1:-$WS/build/test_results/marble_maze}
build="$WS/sanitize"
mkdir -p "$build" "$results"
if ! { cmake -S "$repo/test/sanitize" -B "$build" -DCMAKE_BUILD_TYPE=Debug \
         -DMARBLE_MAZE_DEVEL="$WS/devel" &&
       cmake --build "$build" -j2; } > "$build/build.log" 2>&1; then
  tail -n 20 "$build/build.log"
  echo "the sanitized build failed; the whole log is $build/build.log"
  exit 1
fi
# A shorter soak: the sanitizers make each step some ten times dearer.
status=0
run() {  # run NAME: one sanitized test binary, its JUnit file into the results
  MARBLE_MAZE_SOAK_STEPS=100000 ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    "$build/$1" --gtest_output="xml:$results/gtest-$1.xml" > "$build/$1.log" 2>&1 || status=1
  grep -E "runtime error|ERROR: (Address|Leak)Sanitizer|FAILED" "$build/$1.log" | head -n 20
}
run test_core_sanitized
run test_simulate_cli_sanitized
run test_ros_layer_sanitized
exit $status
