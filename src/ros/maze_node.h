// marble_maze_node: the physics core behind ROS topics, services, parameters, tf and markers.
// It translates; the physics is all in the core.
#pragma once

#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/transform_broadcaster.h>

#include <deque>
#include <memory>
#include <string>

#include "command_queue.h"
#include "marble_maze/BoardTilt.h"
#include "marble_maze/BoardTiltRate.h"
#include "marble_maze/simulation.h"

namespace marble_maze_ros {

class MazeNode {
 public:
  /// Reads the parameters and starts; throws std::runtime_error naming a bad parameter.
  MazeNode(ros::NodeHandle nh, ros::NodeHandle pnh);

 private:
  struct Settings {
    std::string maze = "classic";
    double update_rate = 200.0;  // Hz: how often ROS time is checked for steps due
    double publish_rate = 50.0;  // Hz: marble_state and tf
    double marker_rate = 10.0;   // Hz: marble_marker
    double tilt_timeout = 0.0;   // s of ROS time without commands before the board levels; 0 off
    double auto_reset = 0.0;     // s after the marble finishes before it is reset; 0 off
    std::string world_frame = "world", board_frame = "board", marble_frame = "marble";
  };
  static Settings readSettings(const ros::NodeHandle& pnh, marble_maze::Scene* scene);

  void onTilt(const marble_maze::BoardTilt::ConstPtr& msg);
  void onTiltRate(const marble_maze::BoardTiltRate::ConstPtr& msg);
  void queue(const std_msgs::Header& header, TiltCommand command);
  void onTimer(const ros::TimerEvent&);
  bool onReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool onPause(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool onResume(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);

  void stepUntil(const ros::Time& now);
  void apply(const TiltCommand& command);
  void publish(bool force);
  void publishEvents();
  ros::Time stampOfStep(std::uint64_t step) const;
  ros::Time stampOfTime(double sim_time) const;
  /// Ties the simulation's current step to ROS time `now`.
  void anchor(const ros::Time& now);

  Settings settings_;
  std::unique_ptr<marble_maze::Simulation> sim_;
  CommandQueue commands_;

  ros::Time origin_;  // ROS time of step anchor_step_; zero until the clock runs
  std::uint64_t anchor_step_ = 0;
  ros::Time paused_at_;
  bool paused_ = false;
  ros::Time last_command_;
  bool levelled_after_timeout_ = false;
  ros::Time finished_at_;  // when the marble fell in or reached the goal
  ros::Time last_state_stamp_, last_marker_stamp_;

  ros::Subscriber tilt_sub_, tilt_rate_sub_;
  ros::Publisher state_pub_, event_pub_, maze_pub_, maze_markers_pub_, marble_marker_pub_,
      live_markers_pub_;
  std::deque<marble_maze::Vec3> trail_;  // the marble's recent board-frame positions
  ros::ServiceServer reset_srv_, pause_srv_, resume_srv_;
  tf2_ros::TransformBroadcaster tf_;
  ros::Timer timer_;
};

}  // namespace marble_maze_ros
