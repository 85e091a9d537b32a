#!/usr/bin/env bash
# The demo: roslaunch marble_maze demo.launch. With a display RViz opens (Ctrl-C ends it);
# without one it runs headless, prints progress and a summary, and stops by itself.
set -euo pipefail
export PATH="/usr/bin:$PATH"
. "$(dirname "$0")/workspace.sh"
use_workspace
export ROS_HOME="${ROS_HOME:-$WS/ros_home}"
if [ -n "${DISPLAY:-}" ]; then
  exec roslaunch marble_maze demo.launch "$@"
fi
echo "No display: running the demo headless for 30 s of simulated time."
# The launch ends when the monitor has printed its summary; the timeout only guards a hang.
timeout --signal=INT --kill-after=10 120 \
  roslaunch marble_maze demo.launch rviz:=false headless:=true duration:=30 "$@"
