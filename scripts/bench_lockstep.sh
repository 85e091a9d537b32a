#!/usr/bin/env bash
# ROS lockstep as a roscpp agent runs it (bench/lockstep_agent.cpp): a node with ~lockstep at
# 55 Hz and the `fast` preset on a private master, PERIODS commands each answered by the state
# after it. Prints the periods a second and the node's CPU a period, with only marble_state
# listened to and with every output listened to; then the node's nodelet and the example agent's
# (examples/lockstep_agent_nodelet.cpp) in one manager, and the node and that agent on one thread
# of one process (examples/lockstep_in_process.cpp), with the CPU of that process a period; and
# the physics of a period in process (marble_maze_bench's hand-written loop), all in the same
# run. BASELINE_WS, a workspace built from another commit, adds its node's figures to the run.
set -euo pipefail
# shellcheck source=scripts/workspace.sh
. "$(dirname "$0")/workspace.sh"
export PATH=/usr/bin:$PATH
use_workspace
export ROS_MASTER_URI=http://localhost:11398
periods=${PERIODS:-20000}

# Each case on a master of its own.
master_up() {
  roscore -p 11398 >/dev/null 2>&1 &
  core=$!
  sleep 3
}
master_down() {
  kill "$core"
  wait "$core" || true
}

# figures LOG: the agent's line of figures in LOG, once it is there (within two minutes).
figures() {
  local waited=0
  until grep -q 'periods/s' "$1" || [ $waited -ge 120 ]; do
    sleep 1
    waited=$((waited + 1))
  done
  grep 'periods/s' "$1" || echo "failed"
}

# run WORKSPACE LABEL [agent args...]: that workspace's node and this one's agent.
run() {
  local ws=$1 label=$2
  shift 2
  master_up
  # (its own workspace's libraries first: this one's are on the path, and differ)
  LD_LIBRARY_PATH="$ws/devel/lib:$LD_LIBRARY_PATH" "$ws/devel/lib/marble_maze/marble_maze_node" \
    _lockstep:=0.01818181818181818 _preset:=fast >/dev/null 2>&1 &
  local node=$!
  printf '%-40s ' "$label"
  "$WS/devel/lib/marble_maze/lockstep_agent" _periods:="$periods" _node_pid:="$node" "$@" ||
    echo "failed"
  kill -INT "$node"
  wait "$node" || true
  master_down
}

# nodelets: the node's nodelet and the agent's in one manager of one worker thread (the two take
# turns: a second thread would only add hand-offs).
nodelets() {
  master_up
  rosparam set /marble_maze/lockstep 0.01818181818181818
  rosparam set /marble_maze/preset fast
  rosparam set /agent/periods "$periods"
  local log
  log=$(mktemp)
  /usr/lib/nodelet/nodelet manager __name:=manager _num_worker_threads:=1 >"$log" 2>&1 &
  local manager=$!
  /usr/lib/nodelet/nodelet load marble_maze/MazeNodelet manager __name:=marble_maze \
    >/dev/null 2>&1 &
  local node=$!
  /usr/lib/nodelet/nodelet load marble_maze/LockstepAgentNodelet manager __name:=agent \
    >/dev/null 2>&1 &
  local agent=$!
  printf '%-40s ' "nodelets, node and agent in one:"
  figures "$log"
  kill -INT "$node" "$agent" "$manager"
  wait "$node" "$agent" "$manager" || true
  master_down
  rm -f "$log"
}

# in_process: the node and the agent on one thread of one process (examples/lockstep_in_process.cpp),
# ten times the periods (they take under a tenth of a second).
in_process() {
  master_up
  rosparam set /agent/periods $((periods * 10))
  local log
  log=$(mktemp)
  "$WS/devel/lib/marble_maze/lockstep_in_process" _lockstep:=0.01818181818181818 _preset:=fast \
    >"$log" 2>&1 &
  local both=$!
  printf '%-40s ' "one process, one thread, node and agent:"
  figures "$log"
  kill -INT "$both"
  wait "$both" || true
  master_down
  rm -f "$log"
}

echo "ROS lockstep, 55 Hz, fast preset, $periods periods a case:"
run "$WS" "this node, marble_state alone:"
run "$WS" "this node, every output listened:" _listen_all:=true
nodelets
in_process
if [ -n "${BASELINE_WS:-}" ]; then
  run "$BASELINE_WS" "baseline node, marble_state alone:"
  run "$BASELINE_WS" "baseline node, every output listened:" _listen_all:=true
fi
csv=$(mktemp)
trap 'rm -f "$csv"' EXIT
"$WS/devel/lib/marble_maze/marble_maze_bench" --benchmark_filter='BM_AgentControlStep/envs:0/' \
  --benchmark_out="$csv" --benchmark_out_format=csv >/dev/null 2>&1
awk -F, '/envs:0/ { printf "the physics of a period in process (%s): %.1f us of CPU\n",
  "BM_AgentControlStep/envs:0", $4 / 1000 }' "$csv"
