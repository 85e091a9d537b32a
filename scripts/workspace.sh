# shellcheck shell=bash
# Sourced by the other scripts: WS is the catkin workspace that `make` builds. It lies beside this
# clone, not in it, because rosrun searches the whole package directory for executables and
# would find the workspace's copies too. MARBLE_MAZE_WS overrides it.
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
WS=${MARBLE_MAZE_WS:-$(dirname "$repo")/$(basename "$repo").ws}

# Puts the built workspace on this shell's ROS paths (its setup script reads unset variables).
use_workspace() {
  set +u
  # shellcheck disable=SC1091
  source "$WS/devel/setup.bash"
  set -u
}
