#!/usr/bin/env bash
# Installs the Debian packages marble_maze needs that this machine lacks (Debian 12's own ROS 1),
# or, given package names, those of them that it lacks.
set -euo pipefail

packages=("$@")
[ $# -gt 0 ] || packages=(
  build-essential cmake catkin ros-core-dev ros-message-generation ros-message-runtime
  libeigen3-dev libyaml-cpp-dev libgtest-dev googletest libbenchmark-dev
  python3-rostest python3-rosbag catkin-lint
  libtf2-ros-dev libtf2-eigen-dev libvisualization-msgs-dev libgeometry-msgs-dev libstd-srvs-dev
  libdiagnostic-updater-dev libdynamic-reconfigure-config-init-mutex-dev libnav-msgs-dev
  libdiagnostic-msgs-dev libros-rosgraph-msgs-dev librosbag-dev libtopic-tools-dev
  libnodeletlib-dev libnodelet-dev libnodeletlib-tools pluginlib-dev
  python3-rospy python3-tf2-ros python3-std-srvs python3-visualization-msgs python3-geometry-msgs
  python3-dynamic-reconfigure python3-nav-msgs python3-diagnostic-msgs python3-yaml
  rosbash rviz valgrind python3-matplotlib clang libclang-rt-14-dev
  clang-tidy flake8 shellcheck pybind11-dev python3-pybind11 python3-numpy libcli11-dev
  libdragonbox-dev python3-torch
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "Installing ${missing[*]}"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
