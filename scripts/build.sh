#!/usr/bin/env bash
# Builds marble_maze in a catkin workspace kept out of git (.ws/, the package linked into its src/).
# The build's output goes to .ws/build.log; on failure its end is shown.
set -uo pipefail
# ROS 1's Python tools live in Debian's /usr/bin/python3, whatever python3 comes first on PATH.
export PATH="/usr/bin:$PATH"
cd "$(dirname "$0")/.."
mkdir -p .ws/src
ln -sfn ../.. .ws/src/marble_maze
echo "Building the catkin workspace .ws (log: .ws/build.log)"
if ! (cd .ws && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release -j2 "$@") \
    > .ws/build.log 2>&1; then
  grep -E "error|Error" .ws/build.log | head -n 20
  tail -n 20 .ws/build.log
  echo "build failed; the whole log is .ws/build.log"
  exit 1
fi
