#include "own_clock.h"

#include <algorithm>
#include <cmath>

namespace marble_maze_ros {

namespace {

// At most this much simulated time is caught up in one callback at a real-time factor.
constexpr double kMaxCatchUp = 1.0;  // s
// Run free, each run of steps lasts at most this long, so that commands and services are
// answered in between.
constexpr double kFreeRunSlice = 0.005;  // s of wall time

}  // namespace

void OwnClock::start(ros::NodeHandle& nh) {
  ownClock(nh);
  aimFrom(ros::WallTime::now());
  free_run_ = nh.createWallTimer(
      ros::WallDuration(0.001), [this](const ros::WallTimerEvent&) { tick(ros::WallTime::now()); });
}

void OwnClock::aimFrom(const ros::WallTime& now) {
  start_ = now;
  start_sim_ = c_.session->simulation().time();
}

void OwnClock::tick(const ros::WallTime& now) {
  // ROS time is the simulation's and stands still with it.
  if (c_.session->paused()) return;
  const double factor = c_.settings->real_time_factor;
  if (factor > 0) {
    // As far as the factor allows by now, in slices so that callbacks are answered.
    const double target = start_sim_ + factor * (now - start_).toSec();
    auto due = static_cast<std::int64_t>(
        std::floor((target - c_.session->simulation().time()) / step() + 1e-9));
    const auto most = static_cast<std::int64_t>(std::min(kMaxCatchUp / step(), mostStepsPerCall()));
    if (due > most) {
      skipped_steps_ += due - most;  // cannot keep up: say so, and aim from here
      aimFrom(now);
      due = most;
    }
    if (due > 0) runSayingClock(static_cast<std::uint64_t>(due));
  } else {
    while ((ros::WallTime::now() - now).toSec() < kFreeRunSlice) runSayingClock(100);
  }
  sayClock();
}

void OwnClock::runSayingClock(std::uint64_t count) {
  // /clock is said at each state period's end: ROS time never jumps past a state, so that a
  // node on /use_sim_time can act between any two of them.
  const auto per_state = static_cast<std::uint64_t>(
      std::max(1.0, std::round(1.0 / (c_.settings->publish_rate * step()))));
  while (count > 0) {
    const std::uint64_t to_state = per_state - c_.session->steps() % per_state;
    const std::uint64_t n = std::min(count, to_state);
    c_.run_steps(n, true);
    count -= n;
    if (n == to_state) sayClock();
  }
}

void OwnClock::fillHealth(HealthFigures* f) const {
  f->aimed_factor = c_.settings->real_time_factor;
  f->skipped_steps = skipped_steps_;
}

}  // namespace marble_maze_ros
