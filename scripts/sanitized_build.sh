#!/usr/bin/env bash
# Builds targets of the sanitized project (test/sanitize: the core once with AddressSanitizer and
# UndefinedBehaviorSanitizer, its tests and the fuzzers on it) in WS/sanitize, with Debian's
# clang:  bash scripts/sanitized_build.sh TARGET...
# The workspace's devel space is passed in for the targets that need it, the runner's and the ROS
# layer's tests (their generated message headers are there): make check builds them once the
# workspace is built, while make test builds the core's tests beside the workspace's build.
set -uo pipefail
export PATH="/usr/bin:$PATH"
# shellcheck source=scripts/workspace.sh
. "$(dirname "$0")/workspace.sh"
build="$WS/sanitize"
mkdir -p "$build"
bash "$repo/scripts/install_deps.sh" clang libclang-rt-14-dev >/dev/null
devel=""
case " $* " in
  *" test_simulate_cli_sanitized "* | *" test_ros_layer_sanitized "*) devel="$WS/devel" ;;
esac
if ! { cmake -S "$repo/test/sanitize" -B "$build" -DCMAKE_CXX_COMPILER=clang++ \
         -DCMAKE_BUILD_TYPE=Debug -DMARBLE_MAZE_DEVEL="$devel" &&
       cmake --build "$build" -j2 --target "$@"; } > "$build/build.log" 2>&1; then
  grep -E "error" "$build/build.log" | head -n 20
  tail -n 20 "$build/build.log"
  echo "the sanitized build failed; the whole log is $build/build.log"
  exit 1
fi
