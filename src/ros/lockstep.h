// The ~lockstep time policy: a gym-like loop over plain topics. Each tilt command acts at once
// and advances one control period (~lockstep s, in whole steps), then the state after it is
// published; the node owns /clock, which stands between commands and goes on being said. Paused,
// a command waits for the step service's next step. A change between commands (a reset, a
// place, a load) and a refused command are answered at once, at the stamp of the state before.
#pragma once

#include "time_policy.h"

namespace marble_maze_ros {

class Lockstep : public TimePolicy {
 public:
  using TimePolicy::TimePolicy;
  const char* name() const override { return "lockstep"; }
  void start(ros::NodeHandle& nh) override;
  double command(const ros::Time& stamp, marble_maze::TiltCommand::Kind kind, double roll,
                 double pitch) override;
  void refused() override;
  bool publishesEachStep() const override { return false; }
  bool repeatsStamps() const override { return true; }
  void fillHealth(HealthFigures* figures) const override;
  /// The steps a command advances: the period's whole number of them (the node's step divides
  /// it: fitToLockstep).
  std::uint64_t stepsPerPeriod() const;

 protected:
  bool clockStands() const override { return true; }
};

}  // namespace marble_maze_ros
