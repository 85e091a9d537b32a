// lockstep_in_process: the node and a roscpp agent in lockstep (lockstep_agent.h) in one process
// on one thread. A command and the state answering it pass as pointers through roscpp's callback
// queue, and the thread that publishes one takes the next callback without sleeping: no socket,
// no serialisation, no hand-off between threads (a nodelet manager hands each message from its
// dispatch thread to a worker). The node reads its parameters under ~ as marble_maze_node does
// (and refuses any it does not know), the agent its own under `agent` in the process's namespace
// (`rosparam set agent/periods 20000`); the node goes on serving after the agent's last period.
// scripts/bench_lockstep.sh measures lockstep with it.
#include <ros/ros.h>

#include "lockstep_agent.h"
#include "maze_node.h"
#include "run_node.h"

namespace {

/// The node (parameters under ~) and the agent (under `agent`), on the topics of the process's
/// namespace.
class NodeAndAgent {
 public:
  NodeAndAgent(const ros::NodeHandle& nh, const ros::NodeHandle& pnh)
      : node_(nh, pnh), agent_(nh, ros::NodeHandle(nh, "agent")) {}

 private:
  marble_maze_ros::MazeNode node_;
  marble_maze_examples::LockstepAgent agent_;
};

}  // namespace

int main(int argc, char** argv) {
  // (runNode spins the global queue on this one thread.)
  return marble_maze_ros::runNode<NodeAndAgent>(argc, argv, "marble_maze");
}
