// The ~clock time policy: the node owns /clock (others on /use_sim_time) and runs as fast as it
// can (~real_time_factor 0), in slices so that commands and services are answered in between,
// or at a multiple of real time. Paused, its clock stands still, as a paused Gazebo's does, and
// goes on being said.
#pragma once

#include "time_policy.h"

namespace marble_maze_ros {

class OwnClock : public TimePolicy {
 public:
  using TimePolicy::TimePolicy;
  const char* name() const override { return "own clock"; }
  void start(ros::NodeHandle& nh) override;
  /// What the free-running timer does at wall time `now`: the steps the factor allows by then
  /// (or a slice's worth of steps), then /clock.
  void tick(const ros::WallTime& now);
  void resumed() override { aimFrom(ros::WallTime::now()); }
  std::vector<marble_maze::ParamInfo> liveKeys() const override { return {realTimeFactorKey()}; }
  void realTimeFactorChanged() override { aimFrom(ros::WallTime::now()); }
  void fillHealth(HealthFigures* figures) const override;

 protected:
  bool clockStands() const override { return c_.session->paused(); }

 private:
  /// Takes `count` steps, saying /clock at the end of each state period among them.
  void runSayingClock(std::uint64_t count);
  /// The real-time factor counts from here: wall time `now` and the simulated time now.
  void aimFrom(const ros::WallTime& now);

  ros::WallTimer free_run_;
  ros::WallTime start_;
  double start_sim_ = 0;
};

}  // namespace marble_maze_ros
