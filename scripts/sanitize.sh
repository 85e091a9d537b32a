#!/usr/bin/env bash
# The core's tests under AddressSanitizer and UndefinedBehaviorSanitizer, built beside the
# workspace's own build (WS/sanitize) so that the normal build stays optimised:
#   bash scripts/sanitize.sh [RESULTS_DIR]
# writes its JUnit file into RESULTS_DIR (for make test's count) and exits non-zero on a build
# failure, a failed test or a sanitizer's finding.
set -uo pipefail
export PATH="/usr/bin:$PATH"
. "$(dirname "$0")/workspace.sh"
results=${1:-$WS/build/test_results/marble_maze}
build="$WS/sanitize"
mkdir -p "$build" "$results"
if ! { cmake -S "$repo/test/sanitize" -B "$build" -DCMAKE_BUILD_TYPE=Debug &&
       cmake --build "$build" -j2; } > "$build/build.log" 2>&1; then
  tail -n 20 "$build/build.log"
  echo "the sanitized build failed; the whole log is $build/build.log"
  exit 1
fi
# A shorter soak: the sanitizers make each step some ten times dearer.
MARBLE_MAZE_SOAK_STEPS=100000 ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  "$build/test_core_sanitized" \
  --gtest_output="xml:$results/gtest-test_core_sanitized.xml" > "$build/test.log" 2>&1
status=$?
grep -E "runtime error|ERROR: (Address|Leak)Sanitizer|FAILED" "$build/test.log" | head -n 20
exit $status
