// The node's settings: its own private parameters, and the core's keys set as private
// parameters (as the runner's --set takes them). Read once at start; written back to the
// parameter server so that `rosparam get` shows every value in force.
#pragma once

#include <ros/ros.h>

#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "frames.h"
#include "marble_maze/maze_file.h"
#include "marble_maze/session.h"

namespace marble_maze_ros {

/// Hz: the most often ROS time is looked at (~update_rate's bound, and the timer's however high
/// ~publish_rate is).
constexpr double kMostUpdateRate = 10000.0;

struct NodeSettings {
  std::string maze = "classic";
  double update_rate = 200.0;            // Hz: how often ROS time is looked at for steps due
  double publish_rate = 50.0;            // Hz of simulated time: marble_state, odom and tf
  double marker_rate = 10.0;             // Hz of simulated time: the marble's markers
  marble_maze::SessionSettings session;  // tilt_timeout, rate_timeout, auto_reset
  Frames frames;                         // tf: world -> board -> marble
  bool own_clock = false;                // ~clock: the node owns /clock and runs free
  double real_time_factor = 0;  // with ~clock: a multiple of real time; 0 = as fast as it can
  double lockstep = 0;          // s: each tilt command advances this much; 0 = off
  /// The core's keys given as private parameters, in the key table's order.
  std::vector<std::pair<std::string, std::string>> overrides;
};

/// A private parameter of the node (`key`, resolved for messages) or `fallback` when it is not
/// set; each throws std::runtime_error naming the parameter when it is of another type, or for
/// a number, out of [min, max].
double readNumber(const ros::NodeHandle& pnh, const std::string& key, double fallback, double min,
                  double max);
std::string readText(const ros::NodeHandle& pnh, const std::string& key,
                     const std::string& fallback);
bool readFlag(const ros::NodeHandle& pnh, const std::string& key, bool fallback);

/// Reads every private parameter; throws std::runtime_error naming a bad one (unknown, of the
/// wrong type, out of range, a maze that does not load). `scene` gets the maze and physics.
NodeSettings readSettings(const ros::NodeHandle& pnh, marble_maze::Scene* scene);

/// A maze (a built-in name or a file) with the physics of its file and these settings' keys over
/// it; throws marble_maze::MazeFileError or ParamError.
marble_maze::Scene sceneFor(const std::string& maze, const NodeSettings& settings);
/// In lockstep, the step shortened where it must be to divide ~lockstep's period into whole
/// steps (marble_maze::stepDividing), so that every command advances exactly the period.
void fitToLockstep(const NodeSettings& settings, marble_maze::Params* params);
/// ~world_frame, ~board_frame and ~marble_frame, by default as the node's namespace gives them
/// (framesIn); throws std::runtime_error naming the parameter when they do not make the chain.
Frames readFrames(const ros::NodeHandle& pnh);

/// The burst of tilt commands a node takes in at once (its subscribers' queues), and so the
/// states and events it may publish in answer at once (its publishers' queues).
constexpr std::uint32_t kCommandBurst = 1000;
/// Why the node cannot run `params` with these settings, or "": a lockstep period of more steps
/// or substeps than a command may take, or a rate of messages of simulated time (~publish_rate,
/// ~marker_rate) above one a step. Checked at start and when a maze is loaded or a value changed
/// live, with the same words.
std::string whyNotRunnable(const NodeSettings& settings, const marble_maze::Params& params);

/// Puts every value in force on the parameter server, under the node's private namespace;
/// returns the keys it set.
std::vector<std::string> writeBack(const ros::NodeHandle& pnh, const NodeSettings& settings,
                                   const marble_maze::Params& params);

/// Keeps the core's keys of `changes` (made live) among the settings' overrides, so that a maze
/// loaded later takes them over its file's physics, as it takes those the node started with.
void keepLiveChanges(NodeSettings* settings,
                     const std::vector<std::pair<std::string, std::string>>& changes);

/// The session of `scene` under these settings; throws std::runtime_error naming the parameter
/// (the maze, or the key) when the marble cannot start where the scene puts it.
std::unique_ptr<marble_maze::Session> makeSession(const ros::NodeHandle& pnh,
                                                  const marble_maze::Scene& scene,
                                                  const NodeSettings& settings);

/// "maze 'classic' (21 x 17 x 2 tiles), model rolling, integrator velocity_verlet, step 0.001 s
/// x 1 substeps": what runs, for the node's first log line.
std::string describeRun(const marble_maze::Simulation& sim);

/// The node's own key that changes live beside the core's (dynamic_reconfigure shows it with
/// theirs): its range, read at start and checked at each change, lives here alone.
const marble_maze::ParamInfo& realTimeFactorKey();
/// ~real_time_factor's value in `text`; throws marble_maze::ParamError naming the key.
double parseRealTimeFactor(const std::string& text);

/// Writes the values in force back to the parameter server (writeBack), and when destroyed
/// leaves the private parameters as they were given: each key it wrote back to its given value,
/// or gone, so that a node started later on the same master does not take them for its user's.
class WrittenBack {
 public:
  explicit WrittenBack(const ros::NodeHandle& pnh);
  ~WrittenBack();
  WrittenBack(const WrittenBack&) = delete;
  WrittenBack& operator=(const WrittenBack&) = delete;
  void write(const NodeSettings& settings, const marble_maze::Params& params);

 private:
  ros::NodeHandle pnh_;
  XmlRpc::XmlRpcValue given_;  // the private parameters as given, before any was written back
  bool any_given_ = false;
  std::set<std::string> written_;
};

}  // namespace marble_maze_ros
