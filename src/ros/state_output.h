// What the node tells the ROS graph about the simulation: the scene (the latched `maze` and
// `maze_markers`), the marble (`marble_state`, `odom`, tf world -> board -> marble), its events,
// and the markers that change (`marble_marker`, `live_markers`). Stamps are the caller's.
#pragma once

#include <ros/ros.h>
#include <tf2_msgs/TFMessage.h>

#include <deque>
#include <string>

#include "marble_maze/MarbleState.h"
#include "marble_maze/session.h"
#include "marble_maze/simulation.h"
#include "node_settings.h"
#include "state_messages.h"
#include "tf_watch.h"

namespace marble_maze_ros {

class StateOutput {
 public:
  StateOutput(ros::NodeHandle& nh, const NodeSettings& settings);

  /// The maze for planners and RViz (latched), at the start or, `replacing` another, a load.
  void publishScene(const marble_maze::Simulation& sim, bool replacing);
  /// The latched description alone (the maze and the physics a controller needs), as it stands
  /// after its parameters changed.
  void publishDescription(const marble_maze::Simulation& sim);
  /// The marble's state as a message (stamped).
  marble_maze::MarbleState stateOf(const marble_maze::Simulation& sim,
                                   const ros::Time& stamp) const {
    return marbleStateMessage(sim, stamp, settings_.frames);
  }
  /// marble_state, odom and tf at `stamp`; tf only when the stamp is new (tf listeners refuse
  /// repeated stamps).
  void publishState(const marble_maze::Simulation& sim, const ros::Time& stamp);
  void publishMarkers(const marble_maze::Simulation& sim, const ros::Time& stamp);
  void publishEvent(const marble_maze::Event& event, const ros::Time& stamp);
  /// The state and the markers when due, at `stamp` (the step's, steps lasting `step_ns`): at
  /// the first step at or after each multiple of their period in ROS time (`force`: now), each
  /// stamp later than the one before. A state asked for at an instant already published (a reset
  /// just after a step) goes out with the next step, or, with `repeats_stamps` (lockstep), at
  /// once with the same stamp. The same steps publish in a session and in its replay (but for
  /// those states shown at once, which a replay, stepping on, does not repeat).
  void publishDue(const marble_maze::Session& session, const ros::Time& stamp, std::int64_t step_ns,
                  bool force, bool repeats_stamps = false);
  /// Whether marble_state has a subscriber connected.
  bool stateSubscribed() const { return state_pub_.getNumSubscribers() > 0; }
  /// ROS time went back: stamps may start again from there.
  void clearStamps();

 private:
  NodeSettings settings_;
  ros::Publisher state_pub_, odom_pub_, event_pub_, maze_pub_, maze_markers_pub_,
      marble_marker_pub_, live_markers_pub_, tf_pub_;
  TfWatch tf_watch_;  // says when another node broadcasts these frames
  ros::Time last_tf_stamp_, last_state_stamp_, last_marker_stamp_;
  bool state_pending_ = false;
  std::deque<marble_maze::Vec3> trail_;  // the marble's recent board-frame positions
};

}  // namespace marble_maze_ros
