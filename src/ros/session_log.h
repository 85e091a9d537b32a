// What a bag needs to replay a session exactly: the scene (latched `scene`), every input at the
// step it took effect (`inputs`), and the complete state now and then (latched `snapshot`).
#pragma once

#include <ros/ros.h>

#include <cstdint>
#include <string>

#include "marble_maze/SimInput.h"
#include "marble_maze/session.h"
#include "node_settings.h"
#include "sim_clock.h"

namespace marble_maze_ros {

class SessionLog {
 public:
  SessionLog(ros::NodeHandle& nh, const NodeSettings& settings);

  /// The scene in force: at the start and after a load.
  void scene(const marble_maze::Session& session, const std::string& maze_text,
             const std::string& maze_source);
  /// An input that took effect before step `step`, at ROS time `stamp`; fills index, step, kind
  /// and stamp of `input` and publishes it.
  void input(marble_maze::SimInput input, std::uint8_t kind, std::uint64_t step,
             const ros::Time& stamp);
  /// The tilt commands the session applied in its last run, each at its step, at ROS time
  /// `stamp` (the step's start).
  void applied(const marble_maze::Session& session, const ros::Time& stamp);
  void anchor(const SimClock& clock, std::uint64_t step, const ros::Time& stamp);
  void snapshot(const marble_maze::Session& session, const SimClock& clock, const ros::Time& stamp);

 private:
  NodeSettings settings_;
  ros::Publisher inputs_pub_, scene_pub_, snapshot_pub_;
  std::uint64_t inputs_ = 0;
};

}  // namespace marble_maze_ros
