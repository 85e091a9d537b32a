// marble_maze_node: the marble maze simulation as a ROS node.
#include <ros/ros.h>

#include "maze_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "marble_maze_node");
  try {
    marble_maze_ros::MazeNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("%s", e.what());
    return 1;
  }
  return 0;
}
