#!/usr/bin/env bash
# Why record.launch records with the package's `record` and not `rosbag record`: an agent's burst
# of 1000 tilt commands into a lockstep node, recorded by both at once on a private master; prints
# how many of the node's 1000 inputs each bag holds. RUNS rounds (default 5).
set -uo pipefail
# shellcheck source=scripts/workspace.sh
. "$(dirname "$0")/workspace.sh"
export PATH=/usr/bin:$PATH
set +u
# shellcheck disable=SC1091
source "$WS/devel/setup.bash"
set -u
export ROS_MASTER_URI=http://localhost:11397
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
agent="import math, time, rospy
from marble_maze.msg import BoardTilt
rospy.init_node('burst')
pub = rospy.Publisher('tilt', BoardTilt, queue_size=1000)
while pub.get_num_connections() < 2: time.sleep(0.05)
time.sleep(1.0)
for i in range(1000):
    pub.publish(BoardTilt(roll=0.05 * math.sin(0.01 * i), pitch=0.0))
time.sleep(5.0)"
count="import rosbag, sys
print(sum(1 for _ in rosbag.Bag(sys.argv[1]).read_messages(topics=['/inputs'])))"
for round in $(seq "${RUNS:-5}"); do
  roscore -p 11397 >/dev/null 2>&1 & core=$!
  sleep 3
  roslaunch marble_maze sim.launch lockstep:=0.02 >/dev/null 2>&1 & node=$!
  sleep 4
  rosbag record -O "$dir/rosbag.bag" /inputs >/dev/null 2>&1 & rosbag=$!
  roslaunch marble_maze record.launch node:=false bag:="$dir/record.bag" >/dev/null 2>&1 & record=$!
  sleep 4
  timeout 60 /usr/bin/python3 -c "$agent"
  kill -INT "$rosbag" "$record"; sleep 3
  kill -INT "$node"; sleep 2
  kill "$core"; wait
  echo "round $round: inputs of 1000 in the bag: rosbag record" \
    "$(/usr/bin/python3 -c "$count" "$dir/rosbag.bag"), record" \
    "$(/usr/bin/python3 -c "$count" "$dir/record.bag")"
  rm -f "$dir"/*.bag
done
