// The node's health on /diagnostics (diagnostic_updater, once a second of wall time): the
// real-time factor reached against the one aimed at, steps skipped to catch up, the rate of
// incoming tilt commands, the time since the last one and the command queue's length, with a
// warning where one goes wrong (rqt_robot_monitor and rostopic echo /diagnostics show them).
#pragma once

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace marble_maze_ros {

/// What the node measures, as it stands now.
struct HealthFigures {
  double simulated_time = 0;  ///< s since the start
  double aimed_factor = 1;    ///< times real time aimed at; 0 = as fast as it can
  /// Following ROS time: the factor aimed at is ROS time's own against wall time (1, or what
  /// a /clock from `rosbag play -r` or a stopped one gives), measured, not aimed_factor.
  bool follows_ros_time = false;
  double ros_time = 0;              ///< s, ROS time now
  std::uint64_t skipped_steps = 0;  ///< steps skipped to catch up since the start
  std::uint64_t commands = 0;       ///< tilt commands received since the start
  std::uint64_t lost = 0;           ///< tilt commands lost on the way since the start
  double since_command = -1;        ///< s of ROS time since the last command; -1 none yet
  std::size_t queued = 0;           ///< commands waiting for their step
  double queued_ahead = 0;          ///< s of simulated time until the last of them acts
  bool paused = false;
  /// How the time policy paces the simulation, in the report's words: the summary while all is
  /// well, and what the factor aimed at is.
  std::string running = "running";
  std::string aimed_means = "0: as fast as it can";
  /// s the simulation stands ahead of ROS time (steps taken while paused), waiting for it; 0
  /// when it is not ahead.
  double ahead = 0;
};

class Health {
 public:
  /// `figures` gives them as they stand, asked at each report: a figure the node set only when
  /// it stepped went stale while it did not (paused, a clock standing still).
  Health(ros::NodeHandle& nh, std::function<HealthFigures()> figures);

 private:
  void report(diagnostic_updater::DiagnosticStatusWrapper& status);

  diagnostic_updater::Updater updater_;
  ros::WallTimer timer_;
  std::function<HealthFigures()> figures_;
  HealthFigures now_, before_;
  ros::WallTime before_at_;
};

}  // namespace marble_maze_ros
