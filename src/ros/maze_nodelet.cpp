// marble_maze/MazeNodelet: the node as a nodelet. Loaded into a manager beside an agent's
// nodelet, the tilt commands and the states pass between them as pointers, with no socket and no
// serialisation: the fastest ROS lockstep (doc/agents.md).
#include <nodelet/nodelet.h>

#include <exception>
#include <memory>
#include <pluginlib/class_list_macros.hpp>

#include "maze_node.h"

namespace marble_maze_ros {

class MazeNodelet : public nodelet::Nodelet {
  void onInit() override {
    try {
      node_ = std::make_unique<MazeNode>(getNodeHandle(), getPrivateNodeHandle());
    } catch (const std::exception& e) {  // a bad parameter: this nodelet refuses to load
      NODELET_FATAL("%s", e.what());
      throw;
    }
  }

  std::unique_ptr<MazeNode> node_;
};

}  // namespace marble_maze_ros

PLUGINLIB_EXPORT_CLASS(marble_maze_ros::MazeNodelet, nodelet::Nodelet)
