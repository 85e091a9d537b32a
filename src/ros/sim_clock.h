// How ROS time and the session's steps relate: an anchor ties a step to a ROS time, and each step
// after it lasts the step's length in whole nanoseconds, so that a step's stamp is exact and the
// same wherever it is worked out (the node, its replay, resimulate --bag). Following ROS time (the
// default) the steps due are those whose stamp has come; with ~clock or ~lockstep the node sets
// the time itself and publishes it on /clock.
#pragma once

#include <ros/ros.h>

#include <cstdint>

namespace marble_maze_ros {

class SimClock {
 public:
  /// Ties step `step` (at simulated time `sim_time`) to ROS time `origin`; steps last `step_ns`.
  void anchor(const ros::Time& origin, std::uint64_t step, double sim_time, std::int64_t step_ns);
  bool anchored() const { return anchored_; }
  ros::Time origin() const { return origin_; }
  std::uint64_t anchorStep() const { return anchor_step_; }
  double anchorTime() const { return anchor_time_; }
  std::int64_t stepNs() const { return step_ns_; }

  /// The ROS time at which step `step` starts.
  ros::Time stampOfStep(std::uint64_t step) const;
  /// The ROS time of simulated time `sim_time` (an event inside a step).
  ros::Time stampOf(double sim_time) const;
  /// The first step that starts at or after `stamp` (not before `step_now`).
  std::uint64_t stepAt(const ros::Time& stamp, std::uint64_t step_now) const;
  /// The steps that have started by ROS time `now`: the step count due then.
  std::uint64_t stepsDue(const ros::Time& now) const;

 private:
  bool anchored_ = false;
  ros::Time origin_;  // ROS time at which step anchor_step_ starts
  std::uint64_t anchor_step_ = 0;
  double anchor_time_ = 0;  // s of simulated time at anchor_step_
  std::int64_t step_ns_ = 1000000;
};

/// ROS time rounded down (or up) to a multiple of `step_ns`.
ros::Time onGrid(const ros::Time& t, std::int64_t step_ns, bool up = false);

}  // namespace marble_maze_ros
