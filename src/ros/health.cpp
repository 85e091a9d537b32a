#include "health.h"

namespace marble_maze_ros {

namespace {
/// s: a command queued further ahead than this is more likely a stamp of another clock (wall
/// time sent to a node on simulated time) than a plan.
constexpr double kFarAhead = 10.0;
}  // namespace

Health::Health(ros::NodeHandle& nh, std::function<HealthFigures()> figures)
    : updater_(nh, ros::NodeHandle("~")), figures_(std::move(figures)) {
  updater_.setHardwareID("marble_maze simulation");
  updater_.add("simulation", this, &Health::report);
  before_at_ = ros::WallTime::now();
  // On wall time: with its own fast clock the node would otherwise report a thousand times a
  // second, and with a stopped clock never.
  timer_ = nh.createWallTimer(ros::WallDuration(1.0),
                              [this](const ros::WallTimerEvent&) { updater_.force_update(); });
}

void Health::report(diagnostic_updater::DiagnosticStatusWrapper& status) {
  now_ = figures_();
  const ros::WallTime at = ros::WallTime::now();
  const double wall = (at - before_at_).toSec();
  const double factor = wall > 0 ? (now_.simulated_time - before_.simulated_time) / wall : 0;
  const double command_rate = wall > 0 ? (now_.commands - before_.commands) / wall : 0;
  const std::uint64_t skipped = now_.skipped_steps - before_.skipped_steps;
  // (ROS time's rate needs a sample before this one; a clock that started or went back since
  // has no rate to aim at.)
  const double ros_elapsed = now_.ros_time - before_.ros_time;
  const double aimed = !now_.follows_ros_time                                 ? now_.aimed_factor
                       : before_.ros_time > 0 && ros_elapsed >= 0 && wall > 0 ? ros_elapsed / wall
                                                                              : 0;

  // A period that was paused or waiting for ROS time at either end ran for only part of it:
  // its factor says nothing of the node's speed.
  const bool stood = now_.paused || before_.paused || now_.ahead > 0 || before_.ahead > 0;
  using Level = diagnostic_msgs::DiagnosticStatus;
  if (now_.paused)
    status.summary(Level::OK, "paused");
  else if (skipped > 0)
    status.summaryf(Level::WARN, "fell behind: skipped %llu steps to catch up",
                    static_cast<unsigned long long>(skipped));
  else if (!stood && aimed > 0 && factor < 0.9 * aimed)
    status.summaryf(Level::WARN, "running at %.2f times real time, below the %.2f aimed at", factor,
                    aimed);
  else if (now_.lost > before_.lost)
    status.summaryf(Level::WARN, "%llu tilt commands lost on the way (a burst too large?)",
                    static_cast<unsigned long long>(now_.lost - before_.lost));
  else if (now_.queued > 1000 || now_.queued_ahead > kFarAhead)
    status.summaryf(Level::WARN,
                    "%zu tilt commands wait for their steps, the last %.3g s of simulated time "
                    "ahead (stamped ahead of ROS time?)",
                    now_.queued, now_.queued_ahead);
  else if (now_.ahead > 0)
    status.summaryf(Level::OK,
                    "%.3g s ahead of ROS time (steps taken while paused): waiting for it to "
                    "catch up",
                    now_.ahead);
  else
    status.summary(Level::OK, now_.running);
  status.add("real-time factor", factor);
  status.add("real-time factor aimed at (" + now_.aimed_means + ")", aimed);
  status.add("steps skipped to catch up (last period)", skipped);
  status.add("tilt commands per second", command_rate);
  // (Of ROS time: in lockstep it stands while no command comes, and on the node's own clock
  // while it is paused.)
  if (now_.since_command < 0)
    status.add("seconds of ROS time since the last tilt command", "none yet");
  else
    status.add("seconds of ROS time since the last tilt command", now_.since_command);
  status.add("tilt commands lost on the way (last period)", now_.lost - before_.lost);
  status.add("commands queued", now_.queued);
  status.add("seconds until the last queued command acts", now_.queued_ahead);
  status.add("simulated time (s)", now_.simulated_time);
  status.add("ahead of ROS time (s)", now_.ahead);
  before_ = now_;
  before_at_ = at;
}

}  // namespace marble_maze_ros
