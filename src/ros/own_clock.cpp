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
    if (due > 0) c_.run_steps(static_cast<std::uint64_t>(due), true);
  } else {
    while ((ros::WallTime::now() - now).toSec() < kFreeRunSlice) c_.run_steps(100, true);
  }
  sayClock();
}

void OwnClock::fillHealth(HealthFigures* f) const {
  f->aimed_factor = c_.settings->real_time_factor;
  f->skipped_steps = skipped_steps_;
}

}  // namespace marble_maze_ros
