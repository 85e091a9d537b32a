#include "session_log.h"

#include "marble_maze/SceneDescription.h"
#include "marble_maze/SimSnapshot.h"

namespace marble_maze_ros {
namespace mm = marble_maze;

SessionLog::SessionLog(ros::NodeHandle& nh, const NodeSettings& settings) : settings_(settings) {
  // Deep enough for a burst of steps caught up at once: a recorder loses nothing.
  inputs_pub_ = nh.advertise<marble_maze::SimInput>("inputs", 10000);
  scene_pub_ = nh.advertise<marble_maze::SceneDescription>("scene", 1, true);
  snapshot_pub_ = nh.advertise<marble_maze::SimSnapshot>("snapshot", 1, true);
}

void SessionLog::scene(const mm::Session& session, const std::string& maze_text,
                       const std::string& maze_source) {
  marble_maze::SceneDescription msg;
  msg.header.stamp = ros::Time::now();
  msg.maze_text = maze_text;
  msg.maze_source = maze_source;
  msg.params = mm::paramsText(session.simulation().params());
  msg.tilt_timeout = session.settings().tilt_timeout;
  msg.rate_timeout = session.settings().rate_timeout;
  msg.auto_reset = session.settings().auto_reset;
  msg.publish_rate = settings_.publish_rate;
  msg.marker_rate = settings_.marker_rate;
  scene_pub_.publish(msg);
}

void SessionLog::input(marble_maze::SimInput input, std::uint8_t kind, std::uint64_t step,
                       const ros::Time& stamp) {
  input.header.stamp = stamp;
  input.index = inputs_++;
  input.step = step;
  input.kind = kind;
  inputs_pub_.publish(input);
}

void SessionLog::applied(const marble_maze::Session& session, const ros::Time& stamp) {
  if (inputs_pub_.getNumSubscribers() == 0) {  // (counted all the same: snapshots say how many)
    inputs_ += session.applied().size();
    return;
  }
  for (const marble_maze::TiltCommand& c : session.applied()) {
    marble_maze::SimInput msg;
    msg.roll = c.roll;
    msg.pitch = c.pitch;
    input(msg,
          c.kind == marble_maze::TiltCommand::Kind::Angles ? marble_maze::SimInput::TILT
                                                           : marble_maze::SimInput::TILT_RATE,
          c.step, stamp);
  }
}

void SessionLog::anchor(const SimClock& clock, std::uint64_t step, const ros::Time& stamp) {
  marble_maze::SimInput msg;
  msg.anchor_stamp = clock.origin();
  msg.anchor_time = clock.anchorTime();
  input(msg, marble_maze::SimInput::ANCHOR, step, stamp);
}

void SessionLog::snapshot(const mm::Session& session, const SimClock& clock,
                          const ros::Time& stamp) {
  marble_maze::SimSnapshot msg;
  msg.header.stamp = stamp;
  msg.step = session.steps();
  msg.inputs = inputs_;
  msg.state = session.save();
  msg.params = mm::paramsText(session.simulation().params());
  msg.anchor_stamp = clock.origin();
  msg.anchor_step = clock.anchorStep();
  msg.anchor_time = clock.anchorTime();
  snapshot_pub_.publish(msg);
}

}  // namespace marble_maze_ros
