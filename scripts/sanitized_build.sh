#!/usr/bin/env bash
# Builds targets of the sanitized project (test/sanitize: the core once with AddressSanitizer and
# UndefinedBehaviorSanitizer, its tests and the fuzzers on it) in WS/sanitize, with Debian's
# clang:  bash scripts/sanitized_build.sh TARGET...
# The workspace's devel space is passed in when it is built, so that make check can build the
# runner and the ROS layer's tests too (their generated message headers are there).
set -uo pipefail
export PATH="/usr/bin:$PATH"
# shellcheck source=scripts/workspace.sh
. "$(dirname "$0")/workspace.sh"
build="$WS/sanitize"
mkdir -p "$build"
bash "$repo/scripts/install_deps.sh" clang libclang-rt-14-dev >/dev/null
devel=""
[ -f "$WS/devel/include/marble_maze/MarbleState.h" ] && devel="$WS/devel"
if ! { cmake -S "$repo/test/sanitize" -B "$build" -DCMAKE_CXX_COMPILER=clang++ \
         -DCMAKE_BUILD_TYPE=Debug -DMARBLE_MAZE_DEVEL="$devel" &&
       cmake --build "$build" -j2 --target "$@"; } > "$build/build.log" 2>&1; then
  grep -E "error" "$build/build.log" | head -n 20
  tail -n 20 "$build/build.log"
  echo "the sanitized build failed; the whole log is $build/build.log"
  exit 1
fi
