// marble_maze_node: the core's session behind ROS topics, services, parameters, tf and markers.
// It wires small units together (settings, inputs, outputs, services, reconfigure, health) and
// keeps the one thing that is ROS's alone: how ROS time and the simulation's steps relate, in
// one of three modes:
//  - following ROS time (the default): the steps due are the ROS time elapsed (wall time, or
//    /clock under /use_sim_time), checked at ~update_rate;
//  - ~clock: the node owns /clock and runs as fast as it can (~real_time_factor 0) or at a
//    multiple of real time;
//  - ~lockstep: each tilt command advances one control period, then the state is published.
#pragma once

#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>

#include <cmath>
#include <functional>
#include <memory>
#include <set>
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

namespace marble_maze_ros {

class MazeNode {
 public:
  /// Reads the parameters and starts; throws std::runtime_error naming a bad parameter.
  MazeNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  /// Leaves the private parameters as they were given: the values written back go, so that a
  /// node started later on the same master (rosrun) does not take them for its user's.
  ~MazeNode();
  MazeNode(const MazeNode&) = delete;
  MazeNode& operator=(const MazeNode&) = delete;

 private:
  // Time.
  void onTimer(const ros::TimerEvent&);        // following ROS time
  void onFreeRun(const ros::WallTimerEvent&);  // ~clock
  void runSteps(std::uint64_t count);
  void publishDue(bool force);
  void publishNow();
  ros::Time stampNow() const;
  double simTime() const { return session_->simulation().time(); }
  double step() const { return session_->simulation().params().step; }
  void publishClock();
  /// What /diagnostics reports, as it stands now.
  HealthFigures healthFigures() const;
  /// Ties the current step to ROS time `origin`, and says so on `inputs`.
  void reanchor(const ros::Time& origin);
  /// Runs `change` (another maze, other physics); a step of another length from then on is
  /// re-anchored where the session stood, so that its steps keep to ROS time's rate, and the
  /// commands stamped ahead go to their stamps' steps of that length.
  void keepingTime(const std::function<void()>& change);
  std::int64_t stepNs() const { return std::llround(step() * 1e9); }
  /// How many steps one callback may take, following ROS time or a real-time factor, at the
  /// substeps in force: more are skipped, with a warning.
  double mostStepsPerCall() const;
  /// An input of a service, at the current step, and the state after it.
  void logInput(std::uint8_t kind, const marble_maze::SimInput& input = marble_maze::SimInput());
  std::uint64_t stepsPer(double seconds) const;
  /// Warns when ~lockstep is not a whole number of steps (each command then advances the
  /// nearest whole number of them).
  void warnIfLockstepRounds() const;

  // Inputs and services.
  /// Queues a command at the step its stamp falls on; returns how long (s) it is held.
  double onCommand(const ros::Time& stamp, marble_maze::TiltCommand::Kind kind, double roll,
                   double pitch);
  std::string reset();
  std::string pause();
  std::string resume();
  std::string stepPaused(std::uint32_t steps, marble_maze::MarbleState* after);
  std::string place(const marble_maze::Vec3& position, const marble_maze::Vec3& velocity,
                    const marble_maze::Vec3& spin);
  std::string load(const std::string& maze);
  std::string reconfigure(const Reconfigure::Changes& changes);
  std::string valueOf(const std::string& key) const;

  ros::NodeHandle pnh_;
  /// Writes the values in force back (writeBack), remembering the keys for the destructor.
  void writeBackSettings();

  XmlRpc::XmlRpcValue given_;  // the private parameters as given, before any was written back
  bool any_given_ = false;
  std::set<std::string> written_;  // the keys written back
  NodeSettings settings_;
  std::unique_ptr<marble_maze::Session> session_;
  SimClock clock_;
  std::unique_ptr<StateOutput> out_;
  std::unique_ptr<TiltInput> input_;
  std::unique_ptr<SimServices> services_;
  std::unique_ptr<Reconfigure> reconfigure_;
  std::unique_ptr<Health> health_;
  std::unique_ptr<SessionLog> log_;
  std::string maze_text_, maze_source_;  // the maze file's text, for the scene on `scene`
  bool snapshotted_ = false;
  ros::Publisher clock_pub_;
  ros::Timer timer_;
  ros::WallTimer free_run_;
  ros::WallTimer clock_said_;   // with ~clock or ~lockstep: /clock said while it stands
  ros::WallTimer clock_check_;  // says once if a simulated clock has not come 2 s after start

  ros::Time last_now_;     // the latest ROS time seen (a clock going back is followed)
  ros::Time last_frozen_;  // while paused: when the frozen state was last published
  std::uint64_t skipped_steps_ = 0;
  ros::WallTime free_run_start_;
  double free_run_start_sim_ = 0;
};

}  // namespace marble_maze_ros
