#!/usr/bin/env bash
# Takes a screenshot of the demo as a user sees it in RViz, under a virtual display (Xvfb with
# Mesa's software GL):  bash scripts/screenshot.sh [OUT.png] [SECONDS]
# SECONDS is how long the demo runs after RViz's window appears (default 20).
set -euo pipefail
export PATH="/usr/bin:$PATH"
cd "$(dirname "$0")/.."
out=$(realpath -m "${1:-doc/demo.png}")
seconds=${2:-20}

bash scripts/install_deps.sh xvfb x11-utils imagemagick

. scripts/workspace.sh
use_workspace
run=$(mktemp -d /tmp/marble_maze_shot.XXXXXX)
export ROS_HOME="$run" HOME="$run" XDG_RUNTIME_DIR="$run" MESA_SHADER_CACHE_DIR="$run"
export LIBGL_ALWAYS_SOFTWARE=1 QT_X11_NO_MITSHM=1

display=99
while [ -e "/tmp/.X$display-lock" ]; do display=$((display + 1)); done
Xvfb ":$display" -screen 0 1280x800x24 +extension GLX -nolisten tcp > "$run/xvfb.log" 2>&1 &
xvfb=$!
export DISPLAY=":$display"
# A free port for this demo's own master, so a running roscore is left alone.
export ROS_MASTER_URI="http://localhost:$((11400 + display))"
setsid roslaunch -p "${ROS_MASTER_URI##*:}" marble_maze demo.launch > "$run/demo.log" 2>&1 &
demo=$!
cleanup() {
  kill -INT -- "-$demo" 2>/dev/null || true
  sleep 3
  kill -KILL -- "-$demo" 2>/dev/null || true
  kill "$xvfb" 2>/dev/null || true
}
trap cleanup EXIT

for _ in $(seq 1 180); do
  xwininfo -root -tree 2>/dev/null | grep -q '"[^"]*RViz"' && break
  sleep 0.5
done
xwininfo -root -tree 2>/dev/null | grep -q '"[^"]*RViz"' || {
  tail -n 30 "$run/demo.log"
  echo "RViz did not open; logs in $run" >&2
  exit 1
}
sleep "$seconds"
mkdir -p "$(dirname "$out")"
import -window root "$out"
echo "screenshot: $out (logs in $run)"
