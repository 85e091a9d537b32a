// Listens on /tf for another node broadcasting this node's board or marble frame, and says so,
// naming it: with two authorities for one frame, every tf listener's lookups alternate between
// them (TF_REPEATED_DATA), and nothing else would tell. It listens only while the master lists
// another publisher on /tf (looked at every 2 s), so that a node alone pays nothing.
#pragma once

#include <ros/ros.h>
#include <tf2_msgs/TFMessage.h>

#include "frames.h"

namespace marble_maze_ros {

class TfWatch {
 public:
  TfWatch(ros::NodeHandle& nh, Frames frames);

 private:
  /// Listens while another node publishes /tf, and not otherwise.
  void lookAtPublishers();
  void onTf(const ros::MessageEvent<const tf2_msgs::TFMessage>& event);

  ros::NodeHandle nh_;
  Frames frames_;
  ros::Subscriber tf_sub_;
  ros::WallTimer look_;
};

}  // namespace marble_maze_ros
