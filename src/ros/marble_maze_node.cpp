// marble_maze_node: the marble maze simulation as a ROS node.
#include <ros/ros.h>

#include "maze_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "marble_maze_node");
  // The handles outlive a throwing constructor: with the last handle gone roscpp shuts down and
  // the FATAL message naming the bad parameter would never be printed.
  ros::NodeHandle nh, pnh("~");
  try {
    marble_maze_ros::MazeNode node(nh, pnh);
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("%s", e.what());
    return 1;
  }
  return 0;
}
