// marble_maze_node: the marble maze simulation as a ROS node.
#include "maze_node.h"
#include "run_node.h"

int main(int argc, char** argv) {
  return marble_maze_ros::runNode<marble_maze_ros::MazeNode>(argc, argv, "marble_maze_node");
}
