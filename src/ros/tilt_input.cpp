#include "tilt_input.h"

#include <cmath>

namespace marble_maze_ros {
namespace mm = marble_maze;

TiltInput::TiltInput(ros::NodeHandle& nh, Handler handler,
                     std::function<const mm::Params&()> limits)
    : handler_(std::move(handler)), limits_(std::move(limits)) {
  const auto hints = ros::TransportHints().tcpNoDelay();
  tilt_sub_ = nh.subscribe("tilt", 100, &TiltInput::onTilt, this, hints);
  rate_sub_ = nh.subscribe("tilt_rate", 100, &TiltInput::onTiltRate, this, hints);
  tilt_topic_ = tilt_sub_.getTopic();
  rate_topic_ = rate_sub_.getTopic();
}

void TiltInput::onTilt(const marble_maze::BoardTilt::ConstPtr& msg) {
  if (!std::isfinite(msg->roll) || !std::isfinite(msg->pitch)) {
    ROS_WARN_THROTTLE(1.0, "%s: refused roll=%g pitch=%g (not finite); the board keeps its tilt",
                      tilt_topic_.c_str(), msg->roll, msg->pitch);
    return;
  }
  const double limit = limits_().tilt_limit;
  if (std::abs(msg->roll) > limit || std::abs(msg->pitch) > limit)
    ROS_WARN_THROTTLE(1.0, "%s: roll=%g pitch=%g rad beyond tilt_limit %g rad; clamped",
                      tilt_topic_.c_str(), msg->roll, msg->pitch, limit);
  pass(tilt_topic_, msg->header, mm::TiltCommand::Kind::Angles, msg->roll, msg->pitch);
}

void TiltInput::onTiltRate(const marble_maze::BoardTiltRate::ConstPtr& msg) {
  if (!std::isfinite(msg->roll_rate) || !std::isfinite(msg->pitch_rate)) {
    ROS_WARN_THROTTLE(1.0, "%s: refused roll_rate=%g pitch_rate=%g (not finite); nothing changed",
                      rate_topic_.c_str(), msg->roll_rate, msg->pitch_rate);
    return;
  }
  const double limit = limits_().tilt_rate_limit;
  if (limit > 0 && (std::abs(msg->roll_rate) > limit || std::abs(msg->pitch_rate) > limit))
    ROS_WARN_THROTTLE(1.0,
                      "%s: roll_rate=%g pitch_rate=%g rad/s beyond tilt_rate_limit %g; clamped",
                      rate_topic_.c_str(), msg->roll_rate, msg->pitch_rate, limit);
  pass(rate_topic_, msg->header, mm::TiltCommand::Kind::Rates, msg->roll_rate, msg->pitch_rate);
}

void TiltInput::pass(const std::string& topic, const std_msgs::Header& header,
                     mm::TiltCommand::Kind kind, double roll, double pitch) {
  last_ = ros::Time::now();
  ++received_;
  const double held = handler_(header.stamp.isZero() ? last_ : header.stamp, kind, roll, pitch);
  if (held > kHeldWarning)
    ROS_WARN_THROTTLE(1.0,
                      "%s: command stamped %.9g s is held %.6g s, until the simulation's clock "
                      "reaches its stamp (stamp commands with ros::Time::now(), which follows "
                      "/clock under /use_sim_time, or leave the stamp zero to act at once)",
                      topic.c_str(), header.stamp.toSec(), held);
}

}  // namespace marble_maze_ros
