#include "follow_ros_time.h"

#include <algorithm>

#include "wall_throttle.h"

namespace marble_maze_ros {

namespace {

// At most this much simulated time (or five timer periods, if longer) is caught up in one
// callback; a longer stall (a suspended process, a jump of the clock) is skipped with a warning
// rather than replayed in a burst.
constexpr double kMaxCatchUp = 1.0;  // s

}  // namespace

void FollowRosTime::start(ros::NodeHandle& nh) {
  // At least as often as states are due, or they would leave in bursts, several a tick.
  const double rate =
      std::min(std::max(c_.settings->update_rate, c_.settings->publish_rate), kMostUpdateRate);
  timer_ = nh.createTimer(ros::Duration(1.0 / rate),
                          [this](const ros::TimerEvent&) { tick(ros::Time::now()); });
  // (On the wall's clock: a timer of ROS time does not fire while a simulated clock has not
  // started.)
  clock_check_ = nh.createWallTimer(
      ros::WallDuration(2.0),
      [](const ros::WallTimerEvent&) {
        if (ros::Time::now().isZero())
          ROS_INFO("marble_maze: waiting for /clock (/use_sim_time is true and no clock has come)");
      },
      true);
}

void FollowRosTime::tick(const ros::Time& now) {
  if (now.isZero()) return;     // a simulated clock that has not started (clock_check_ says so)
  if (!c_.clock->anchored()) {  // the first tick of a running clock
    // Steps on a grid of ROS time (multiples of the step), so that two nodes given the same
    // stamped commands apply them at the same instants: `rosbag play` of a session's commands
    // into a fresh node then follows the session.
    c_.reanchor(onGrid(now, stepNs()));
    last_now_ = now;
    c_.publish_state(stateStamp(), true);
    return;
  }
  if (now < last_now_) {
    ROS_WARN(
        "ROS time went back by %.3f s (a bag looping? a restarted clock?): following it, the "
        "marble back on the start",
        (last_now_ - now).toSec());
    // A bag looping plays its session again from the start: so does the simulation.
    c_.restart(onGrid(now, stepNs()));
    last_now_ = now;
    c_.publish_state(stateStamp(), true);
    return;
  }
  last_now_ = now;
  if (c_.session->paused()) {
    // The frozen state goes on being published, so that tf does not go stale.
    // Each is due a publish period after the last was due, not after it went out: the timer's
    // ticks then cost no period its lateness, and the states keep the publish rate.
    const ros::Duration period(1.0 / c_.settings->publish_rate);
    if (next_frozen_.isZero() || now >= next_frozen_) {
      next_frozen_ = next_frozen_.isZero() || now - next_frozen_ >= period ? now + period
                                                                           : next_frozen_ + period;
      c_.publish_state(stateStamp(), true);
    }
    return;
  }
  // (Negative after steps taken while paused, which keep their exact stamps: nothing is due, and
  // nothing is published, until ROS time has caught up; /diagnostics says how far ahead.)
  auto due = static_cast<std::int64_t>(c_.clock->stepsDue(now)) -
             static_cast<std::int64_t>(c_.session->steps());
  const auto most = static_cast<std::int64_t>(
      std::min(std::max(kMaxCatchUp, 5.0 / c_.settings->update_rate) / step(), mostStepsPerCall()));
  if (due > most) {
    MARBLE_MAZE_WARN_WALL_THROTTLE(5.0, "simulation fell %.3g s behind ROS time; skipping ahead",
                                   static_cast<double>(due - most) * step());
    skipped_steps_ += due - most;
    // The steps taken now end at now's step on the grid.
    c_.reanchor(ros::Time().fromNSec(onGrid(now, stepNs()).toNSec() - most * stepNs()));
    due = most;
  }
  if (due > 0) c_.run_steps(static_cast<std::uint64_t>(due), true);
}

void FollowRosTime::reanchorAhead() {
  if (c_.clock->anchored())
    c_.reanchor(onGrid(std::max(ros::Time::now(), stampNow()), stepNs(), true));
}

void FollowRosTime::paused() {
  next_frozen_ = ros::Time();
  reanchorAhead();  // steps taken while paused (`step`) follow on from here in simulated time
}

void FollowRosTime::resumed() {
  // The simulation takes up where it stopped: the paused time is not simulated. Steps taken
  // while paused put it ahead of ROS time, which then catches up.
  reanchorAhead();
}

ros::Time FollowRosTime::stateStamp() const {
  // Paused, the frozen state is stamped with the ROS time that passes.
  return c_.session->paused() ? std::max(ros::Time::now(), stampNow()) : stampNow();
}

void FollowRosTime::fillHealth(HealthFigures* f) const {
  f->aimed_factor = 1;
  f->follows_ros_time = true;
  f->aimed_means = "ROS time's own";
  f->skipped_steps = skipped_steps_;
  if (c_.clock->anchored()) f->ahead = std::max(0.0, (stampNow() - ros::Time::now()).toSec());
}

}  // namespace marble_maze_ros
