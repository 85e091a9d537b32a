#include "sim_clock.h"

#include <algorithm>

namespace marble_maze_ros {

void SimClock::anchor(const ros::Time& origin, std::uint64_t step, double sim_time,
                      std::int64_t step_ns) {
  origin_ = origin;
  anchor_step_ = step;
  anchor_time_ = sim_time;
  step_ns_ = std::max<std::int64_t>(1, step_ns);
  anchored_ = true;
}

ros::Time SimClock::stampOfStep(std::uint64_t step) const {
  const auto steps = static_cast<std::int64_t>(step) - static_cast<std::int64_t>(anchor_step_);
  return ros::Time().fromNSec(origin_.toNSec() + steps * step_ns_);
}

ros::Time SimClock::stampOf(double sim_time) const {
  return origin_ + ros::Duration(sim_time - anchor_time_);
}

std::uint64_t SimClock::stepAt(const ros::Time& stamp, std::uint64_t step_now) const {
  const std::int64_t ahead =
      static_cast<std::int64_t>(stamp.toNSec()) - static_cast<std::int64_t>(origin_.toNSec());
  if (ahead <= 0) return std::max(step_now, anchor_step_);
  const std::uint64_t step =
      anchor_step_ + static_cast<std::uint64_t>((ahead + step_ns_ - 1) / step_ns_);
  return std::max(step_now, step);
}

std::uint64_t SimClock::stepsDue(const ros::Time& now) const {
  const std::int64_t elapsed =
      static_cast<std::int64_t>(now.toNSec()) - static_cast<std::int64_t>(origin_.toNSec());
  if (elapsed < 0) return anchor_step_;
  return anchor_step_ + static_cast<std::uint64_t>(elapsed / step_ns_);
}

ros::Time onGrid(const ros::Time& t, std::int64_t step_ns, bool up) {
  const auto ns = static_cast<std::int64_t>(t.toNSec());
  std::int64_t down = ns - ns % step_ns;
  if (up && down < ns) down += step_ns;
  return ros::Time().fromNSec(down);
}

}  // namespace marble_maze_ros
