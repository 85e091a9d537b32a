#include "sim_clock.h"

#include <cmath>

namespace marble_maze_ros {

ros::Time SimClock::stampOf(double sim_time) const {
  return origin_ + ros::Duration(sim_time - anchor_sim_);
}

std::uint64_t SimClock::stepAt(const ros::Time& stamp, std::uint64_t step_now, double sim_now,
                               double step) const {
  // Steps still to come before the stamp, rounding a stamp within a nanosecond of a step's start
  // to that step (stamps carry nanoseconds, steps doubles).
  const double ahead = (stamp - stampOf(sim_now)).toSec();
  if (ahead <= 0) return step_now;
  return step_now + static_cast<std::uint64_t>(std::ceil(ahead / step - 1e-6));
}

void SimClock::anchor(const ros::Time& now, double sim_time) {
  origin_ = now;
  anchor_sim_ = sim_time;
  anchored_ = true;
}

}  // namespace marble_maze_ros
