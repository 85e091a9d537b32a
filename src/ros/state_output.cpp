#include "state_output.h"

#include <nav_msgs/Odometry.h>
#include <tf2_eigen/tf2_eigen.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <cmath>

#include "marble_maze/MazeEvent.h"
#include "maze_description.h"
#include "maze_markers.h"

namespace marble_maze_ros {
namespace mm = marble_maze;

StateOutput::StateOutput(ros::NodeHandle& nh, const NodeSettings& settings) : settings_(settings) {
  // A publisher drops its oldest message past its queue: deep enough that a lockstep agent's
  // burst of commands (tilt's queue) is answered state for state, and that a recorder the
  // machine holds up for a moment loses none.
  state_pub_ = nh.advertise<marble_maze::MarbleState>("marble_state", kCommandBurst);
  odom_pub_ = nh.advertise<nav_msgs::Odometry>("odom", 10);
  event_pub_ = nh.advertise<marble_maze::MazeEvent>("events", kCommandBurst);
  maze_pub_ = nh.advertise<marble_maze::MazeDescription>("maze", 1, true);
  maze_markers_pub_ = nh.advertise<visualization_msgs::MarkerArray>("maze_markers", 1, true);
  marble_marker_pub_ = nh.advertise<visualization_msgs::Marker>("marble_marker", 10);
  live_markers_pub_ = nh.advertise<visualization_msgs::MarkerArray>("live_markers", 1);
}

void StateOutput::publishDescription(const mm::Simulation& sim) {
  maze_pub_.publish(describe({sim.maze(), sim.params()}, settings_.board_frame));
}

void StateOutput::publishScene(const mm::Simulation& sim, bool replacing) {
  publishDescription(sim);
  visualization_msgs::MarkerArray markers = mazeMarkers(sim.maze(), settings_.board_frame);
  if (replacing) {  // the old maze's markers of kinds and sizes the new one lacks go
    visualization_msgs::Marker clear;
    clear.action = visualization_msgs::Marker::DELETEALL;
    clear.header.frame_id = settings_.board_frame;
    markers.markers.insert(markers.markers.begin(), clear);
  }
  maze_markers_pub_.publish(markers);
  trail_.clear();
}

marble_maze::MarbleState StateOutput::stateOf(const mm::Simulation& sim,
                                              const ros::Time& stamp) const {
  const mm::Marble& m = sim.marble();
  marble_maze::MarbleState state;
  state.header.stamp = stamp;
  state.header.frame_id = settings_.world_frame;
  state.position = tf2::toMsg(sim.worldPosition());
  tf2::toMsg(m.velocity, state.velocity);
  tf2::toMsg(m.angular_velocity, state.angular_velocity);
  state.position_in_board = tf2::toMsg(sim.marbleInBoard());
  state.roll = sim.board().roll();
  state.pitch = sim.board().pitch();
  state.contacts = static_cast<std::uint8_t>(std::min(m.contacts, 255));
  state.in_hole = m.phase == mm::MarblePhase::InHole;
  state.at_goal = m.phase == mm::MarblePhase::AtGoal;
  state.off_board = m.phase == mm::MarblePhase::OffBoard;
  return state;
}

void StateOutput::publishState(const mm::Simulation& sim, const ros::Time& stamp) {
  const mm::Marble& m = sim.marble();
  state_pub_.publish(stateOf(sim, stamp));

  nav_msgs::Odometry odom;  // the twist in the child frame, as REP 105's odometry has it
  odom.header.stamp = stamp;
  odom.header.frame_id = settings_.world_frame;
  odom.child_frame_id = settings_.marble_frame;
  odom.pose.pose.position = tf2::toMsg(sim.worldPosition());
  odom.pose.pose.orientation = tf2::toMsg(m.orientation);
  const mm::Mat3 to_marble = m.orientation.toRotationMatrix().transpose();
  tf2::toMsg(mm::Vec3(to_marble * m.velocity), odom.twist.twist.linear);
  tf2::toMsg(mm::Vec3(to_marble * m.angular_velocity), odom.twist.twist.angular);
  odom_pub_.publish(odom);

  if (stamp <= last_tf_stamp_) return;
  last_tf_stamp_ = stamp;
  const mm::Mat3& board = sim.board().rotation();
  Eigen::Isometry3d world_to_board = Eigen::Isometry3d::Identity();
  world_to_board.linear() = board;
  world_to_board.translation() = sim.params().board_position;
  geometry_msgs::TransformStamped board_tf = tf2::eigenToTransform(world_to_board);
  board_tf.header.stamp = stamp;
  board_tf.header.frame_id = settings_.world_frame;
  board_tf.child_frame_id = settings_.board_frame;
  Eigen::Isometry3d board_to_marble = Eigen::Isometry3d::Identity();
  board_to_marble.translation() = sim.marbleInBoard();
  board_to_marble.linear() = board.transpose() * m.orientation.toRotationMatrix();
  geometry_msgs::TransformStamped marble_tf = tf2::eigenToTransform(board_to_marble);
  marble_tf.header.stamp = stamp;
  marble_tf.header.frame_id = settings_.board_frame;
  marble_tf.child_frame_id = settings_.marble_frame;
  tf_.sendTransform({board_tf, marble_tf});
}

void StateOutput::publishMarkers(const mm::Simulation& sim, const ros::Time& stamp) {
  visualization_msgs::Marker marble =
      marbleMarker(sim.params().marble_radius, settings_.marble_frame);
  marble.header.stamp = stamp;
  marble_marker_pub_.publish(marble);
  // The trail: the last 3 s at the marker rate; a jump (a reset, a place) starts a new one.
  const mm::Vec3 here = sim.marbleInBoard();
  if (!trail_.empty() && (trail_.back() - here).norm() > 0.05) trail_.clear();
  trail_.push_back(here);
  while (trail_.size() > 3 * settings_.marker_rate) trail_.pop_front();
  visualization_msgs::MarkerArray live =
      liveMarkers(sim.maze(), {trail_.begin(), trail_.end()}, sim.params().marble_radius,
                  sim.board().roll(), sim.board().pitch(), settings_.board_frame);
  for (auto& m : live.markers) m.header.stamp = stamp;
  live_markers_pub_.publish(live);
}

void StateOutput::clearStamps() {
  last_tf_stamp_ = last_state_stamp_ = last_marker_stamp_ = ros::Time();
  state_pending_ = false;
}

void StateOutput::publishDue(const mm::Session& session, const ros::Time& stamp,
                             std::int64_t step_ns, bool force, bool repeats_stamps) {
  const mm::Simulation& sim = session.simulation();
  // Whether a multiple of the period falls in this step: (stamp - step, stamp].
  const auto due = [&](double rate) {
    const std::int64_t period = std::max<std::int64_t>(1, std::llround(1e9 / rate));
    const auto now = static_cast<std::int64_t>(stamp.toNSec());
    return now / period != (now - step_ns) / period;
  };
  // Where time moves only with commands (lockstep), a change between them (a reset, a place, a
  // load) is shown at once, at the stamp of the state before it (tf, whose stamps must
  // increase, follows with the next period).
  const bool again = force && repeats_stamps && stamp == last_state_stamp_;
  if (force || state_pending_ || due(settings_.publish_rate)) {
    state_pending_ = stamp <= last_state_stamp_ && !again;
    if (!state_pending_) {
      last_state_stamp_ = stamp;
      publishState(sim, stamp);
    }
  }
  if ((force || due(settings_.marker_rate)) && stamp > last_marker_stamp_) {
    last_marker_stamp_ = stamp;
    publishMarkers(sim, stamp);
  }
}

void StateOutput::publishEvent(const mm::Event& e, const ros::Time& stamp) {
  marble_maze::MazeEvent msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = settings_.board_frame;
  switch (e.kind) {
    case mm::EventKind::Collision:
      msg.kind = marble_maze::MazeEvent::COLLISION;
      break;
    case mm::EventKind::Hole:
      msg.kind = marble_maze::MazeEvent::HOLE;
      break;
    case mm::EventKind::Goal:
      msg.kind = marble_maze::MazeEvent::GOAL;
      break;
    case mm::EventKind::OffBoard:
      msg.kind = marble_maze::MazeEvent::OFF_BOARD;
      break;
  }
  msg.tile_x = e.tile.x();
  msg.tile_y = e.tile.y();
  msg.tile_z = e.tile.z();
  msg.impact_speed = e.speed;
  event_pub_.publish(msg);
  if (e.kind != mm::EventKind::Collision)
    ROS_INFO("t=%.3f s: %s at tile (%d, %d, %d)", e.time, mm::toString(e.kind).c_str(), e.tile.x(),
             e.tile.y(), e.tile.z());
}

}  // namespace marble_maze_ros
