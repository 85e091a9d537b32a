#!/usr/bin/env bash
# The demo: roslaunch marble_maze demo.launch, where the autopilot plays the classic maze. With a
# display RViz opens (Ctrl-C ends it); without one it runs headless: progress lines, then a
# summary when the marble reaches the goal, and the exit status says whether it did.
set -euo pipefail
export PATH="/usr/bin:$PATH"
# shellcheck source=scripts/workspace.sh
. "$(dirname "$0")/workspace.sh"
use_workspace
export ROS_HOME="${ROS_HOME:-$WS/ros_home}"
if [ -n "${DISPLAY:-}" ]; then
  exec roslaunch marble_maze demo.launch "$@"
fi
echo "No display: running the demo headless until the marble reaches the goal (at most 60 s of"
echo "simulated time)."
# The monitor runs here rather than in the launch, so that when it ends the launch is stopped
# like Ctrl-C stops it; the timeout only guards a hang.
roslaunch marble_maze demo.launch headless:=true monitor:=false "$@" &
launch=$!
# The monitor needs the master that roslaunch starts.
for _ in $(seq 100); do
  /usr/bin/python3 -c "import rosgraph, sys; sys.exit(not rosgraph.is_master_online())" && break
  sleep 0.2
done
status=0
timeout --signal=INT --kill-after=10 150 rosrun marble_maze demo_monitor _duration:=60 || status=$?
kill -INT "$launch" 2>/dev/null || true
wait "$launch" || true
exit "$status"
