#!/usr/bin/env bash
# Builds marble_maze in a catkin workspace kept out of git (see workspace.sh: beside this clone,
# the package linked into its src/). The build's output goes to WS/build.log; on failure its end
# is shown.
set -uo pipefail
# ROS 1's Python tools live in Debian's /usr/bin/python3, whatever python3 comes first on PATH.
export PATH="/usr/bin:$PATH"
# shellcheck source=scripts/workspace.sh
. "$(dirname "$0")/workspace.sh"
mkdir -p "$WS/src"
ln -sfn "$repo" "$WS/src/marble_maze"
echo "Building the catkin workspace $WS (log: $WS/build.log)"
if ! (cd "$WS" && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_EXPORT_COMPILE_COMMANDS=ON -j2 "$@") \
    > "$WS/build.log" 2>&1; then
  grep -E "error|Error" "$WS/build.log" | head -n 20
  tail -n 20 "$WS/build.log"
  echo "build failed; the whole log is $WS/build.log"
  exit 1
fi
