// The default time policy: the simulation follows ROS time (wall time, or /clock under
// /use_sim_time). The steps due are those whose stamp has come, on a grid of ROS time (multiples
// of the step), looked at ~update_rate times a second; a stall is caught up a second at a time at
// most, a longer one skipped with a warning; a clock that goes back restarts the session.
// Paused, the frozen state goes on being published, stamped with the ROS time that passes.
#pragma once

#include "time_policy.h"

namespace marble_maze_ros {

class FollowRosTime : public TimePolicy {
 public:
  using TimePolicy::TimePolicy;
  const char* name() const override { return "ROS time"; }
  void start(ros::NodeHandle& nh) override;
  /// What the timer does at ROS time `now`: the steps due, caught up.
  void tick(const ros::Time& now);
  void paused() override;
  void resumed() override;
  ros::Time stateStamp() const override;
  void fillHealth(HealthFigures* figures) const override;

 private:
  /// Ties the step now to ROS time at or after both `now` and the simulation's stamp.
  void reanchorAhead();

  ros::Timer timer_;
  ros::WallTimer clock_check_;  // says once if a simulated clock has not come 2 s after start
  ros::Time last_now_;          // the latest ROS time seen (a clock going back is followed)
  ros::Time next_frozen_;       // while paused: when the frozen state is next due
};

}  // namespace marble_maze_ros
