// marble_maze_node: the core's session behind ROS topics, services, parameters, tf and markers.
// It wires small units together (settings, inputs, outputs, services, reconfigure, health) and
// the time policy chosen at start (time_policy.h), which decides when the session advances.
#pragma once

#include <ros/ros.h>

#include <functional>
#include <memory>
#include <string>

#include "health.h"
#include "marble_maze/session.h"
#include "node_settings.h"
#include "reconfigure.h"
#include "session_log.h"
#include "sim_clock.h"
#include "sim_services.h"
#include "state_output.h"
#include "tilt_input.h"
#include "time_policy.h"

namespace marble_maze_ros {

class MazeNode {
 public:
  /// Reads the parameters and starts; throws std::runtime_error naming a bad parameter.
  MazeNode(ros::NodeHandle nh, const ros::NodeHandle& pnh);
  MazeNode(const MazeNode&) = delete;
  MazeNode& operator=(const MazeNode&) = delete;

 private:
  // What the time policy drives.
  void runSteps(std::uint64_t count, bool publish_each);
  void publishState(const ros::Time& stamp, bool force);
  void publishNow();
  void reanchor(const ros::Time& origin);
  void restart(const ros::Time& now);
  ros::Time stampNow() const { return clock_.stampOfStep(session_->steps()); }
  std::int64_t stepNs() const;
  /// What /diagnostics reports, as it stands now.
  HealthFigures healthFigures() const;
  /// An input of a service, at the current step, and the state after it.
  void logInput(std::uint8_t kind, const marble_maze::SimInput& input = marble_maze::SimInput());

  // Services.
  std::string reset();
  std::string pause();
  std::string resume();
  std::string stepPaused(std::uint32_t steps, marble_maze::MarbleState* after);
  std::string place(const marble_maze::Vec3& position, const marble_maze::Vec3& velocity,
                    const marble_maze::Vec3& spin);
  std::string load(const std::string& maze);
  std::string reconfigure(const Reconfigure::Changes& changes);
  std::string valueOf(const std::string& key) const;
  /// After the maze or the physics changed: the values in force written back.
  void changed();

  WrittenBack written_;  // first made, last gone: the parameters left as they were given
  NodeSettings settings_;
  std::unique_ptr<marble_maze::Session> session_;
  SimClock clock_;
  std::unique_ptr<SessionLog> log_;
  std::unique_ptr<StateOutput> out_;
  std::unique_ptr<TimePolicy> time_;
  std::unique_ptr<TiltInput> input_;
  std::unique_ptr<SimServices> services_;
  std::unique_ptr<Reconfigure> reconfigure_;
  std::unique_ptr<Health> health_;
  std::string maze_text_, maze_source_;  // the maze file's text, for the scene on `scene`
  bool snapshotted_ = false;
};

}  // namespace marble_maze_ros
