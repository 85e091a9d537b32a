// marble_maze/LockstepAgentNodelet: a roscpp agent in lockstep (lockstep_agent.h) as a nodelet,
// to load into the manager of a MazeNodelet started with ~lockstep. It prints its figures in the
// manager's output. scripts/bench_lockstep.sh measures lockstep with it.
#include <nodelet/nodelet.h>

#include <memory>
#include <pluginlib/class_list_macros.hpp>

#include "lockstep_agent.h"

namespace marble_maze_examples {

class LockstepAgentNodelet : public nodelet::Nodelet {
  void onInit() override {
    agent_ = std::make_unique<LockstepAgent>(getNodeHandle(), getPrivateNodeHandle());
  }

  std::unique_ptr<LockstepAgent> agent_;
};

}  // namespace marble_maze_examples

PLUGINLIB_EXPORT_CLASS(marble_maze_examples::LockstepAgentNodelet, nodelet::Nodelet)
