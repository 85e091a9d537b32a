#include "state_output.h"

#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <boost/make_shared.hpp>
#include <cmath>

#include "marble_maze/MazeEvent.h"
#include "maze_description.h"
#include "maze_markers.h"
#include "state_messages.h"

namespace marble_maze_ros {
namespace mm = marble_maze;

StateOutput::StateOutput(ros::NodeHandle& nh, const NodeSettings& settings)
    : settings_(settings), tf_watch_(nh, settings.frames) {
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
  tf_pub_ = nh.advertise<tf2_msgs::TFMessage>("/tf", 100);  // as tf2_ros's broadcaster does
}

void StateOutput::publishDescription(const mm::Simulation& sim) {
  maze_pub_.publish(describe({sim.maze(), sim.params()}, settings_.frames.board));
}

void StateOutput::publishScene(const mm::Simulation& sim, bool replacing) {
  publishDescription(sim);
  visualization_msgs::MarkerArray markers = mazeMarkers(sim.maze(), settings_.frames.board);
  if (replacing) {  // the old maze's markers of kinds and sizes the new one lacks go
    visualization_msgs::Marker clear;
    clear.action = visualization_msgs::Marker::DELETEALL;
    clear.header.frame_id = settings_.frames.board;
    markers.markers.insert(markers.markers.begin(), clear);
  }
  maze_markers_pub_.publish(markers);
  trail_.clear();
}

void StateOutput::publishState(const mm::Simulation& sim, const ros::Time& stamp) {
  // Each message is built only when someone listens: a lockstep agent that reads marble_state
  // alone pays for nothing else.
  // (marble_state goes as a shared message: a subscriber in the same process, a nodelet, gets it
  // without a copy and without a wake of roscpp's poll thread.)
  if (state_pub_.getNumSubscribers() > 0)
    state_pub_.publish(boost::make_shared<marble_maze::MarbleState>(
        marbleStateMessage(sim, stamp, settings_.frames)));
  if (odom_pub_.getNumSubscribers() > 0)
    odom_pub_.publish(odometryMessage(sim, stamp, settings_.frames));
  if (stamp <= last_tf_stamp_) return;
  last_tf_stamp_ = stamp;
  if (tf_pub_.getNumSubscribers() == 0) return;
  const auto transforms = boardAndMarbleTransforms(sim, stamp, settings_.frames);
  tf2_msgs::TFMessage tf;
  tf.transforms.assign(transforms.begin(), transforms.end());
  tf_pub_.publish(tf);
}

void StateOutput::publishMarkers(const mm::Simulation& sim, const ros::Time& stamp) {
  if (marble_marker_pub_.getNumSubscribers() == 0 && live_markers_pub_.getNumSubscribers() == 0)
    return;  // (the trail starts again when someone looks)
  visualization_msgs::Marker marble =
      marbleMarker(sim.params().marble_radius, settings_.frames.marble);
  marble.header.stamp = stamp;
  marble_marker_pub_.publish(marble);
  // The trail: the last 3 s at the marker rate; a jump (a reset, a place) starts a new one.
  const mm::Vec3 here = sim.marbleInBoard();
  if (!trail_.empty() && (trail_.back() - here).norm() > 0.05) trail_.clear();
  trail_.push_back(here);
  while (trail_.size() > 3 * settings_.marker_rate) trail_.pop_front();
  visualization_msgs::MarkerArray live =
      liveMarkers(sim.maze(), {trail_.begin(), trail_.end()}, sim.params().marble_radius,
                  sim.board().roll(), sim.board().pitch(), settings_.frames.board);
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
  msg.header.frame_id = settings_.frames.board;
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
