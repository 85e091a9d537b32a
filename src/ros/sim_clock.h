// How ROS time and the session's steps relate. Following ROS time (the default), an anchor ties
// a step to a ROS time and the steps due are the ROS time elapsed since; with ~clock or
// ~lockstep the node sets the time itself and publishes it on /clock.
#pragma once

#include <ros/ros.h>

#include <cstdint>

namespace marble_maze_ros {

class SimClock {
 public:
  /// The ROS time of simulated time `sim_time` (s).
  ros::Time stampOf(double sim_time) const;
  /// The first step that starts at or after `stamp`, given the step now and its length.
  std::uint64_t stepAt(const ros::Time& stamp, std::uint64_t step_now, double sim_now,
                       double step) const;
  /// Ties simulated time `sim_time` to ROS time `now`.
  void anchor(const ros::Time& now, double sim_time);
  bool anchored() const { return anchored_; }
  ros::Time origin() const { return origin_; }
  double anchorTime() const { return anchor_sim_; }
  /// Simulated time due at ROS time `now` (following ROS time).
  double due(const ros::Time& now) const { return anchor_sim_ + (now - origin_).toSec(); }

 private:
  bool anchored_ = false;
  ros::Time origin_;       // ROS time of anchor_sim_
  double anchor_sim_ = 0;  // s of simulated time
};

}  // namespace marble_maze_ros
