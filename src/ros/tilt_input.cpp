#include "tilt_input.h"

#include <cmath>

#include "marble_maze/params.h"
#include "node_settings.h"
#include "wall_throttle.h"

namespace marble_maze_ros {
namespace mm = marble_maze;

TiltInput::TiltInput(ros::NodeHandle& nh, Handler handler,
                     std::function<const mm::Params&()> limits, std::function<void()> refused)
    : handler_(std::move(handler)), limits_(std::move(limits)), refused_(std::move(refused)) {
  const auto hints = ros::TransportHints().tcpNoDelay();
  // Deep queues: in lockstep each command runs its control period before the next is read, and an
  // agent may send a burst.
  tilt_sub_ = nh.subscribe("tilt", kCommandBurst, &TiltInput::onTilt, this, hints);
  rate_sub_ = nh.subscribe("tilt_rate", kCommandBurst, &TiltInput::onTiltRate, this, hints);
  tilt_topic_ = tilt_sub_.getTopic();
  rate_topic_ = rate_sub_.getTopic();
}

void TiltInput::checkNoneLost(const std::string& topic, const std::string& publisher,
                              const std_msgs::Header& header) {
  const std::uint64_t lost = gaps_.take(topic + " " + publisher, header.seq);
  if (lost == 0) return;
  lost_ += lost;
  lost_total_ += lost;
  // Said at most once a second of wall time (ROS time may run a thousand times faster), with
  // every command lost since.
  const ros::WallTime now = ros::WallTime::now();
  if (!said_lost_.isZero() && (now - said_lost_).toSec() < 1.0) return;
  said_lost_ = now;
  ROS_WARN(
      "%s: %llu commands from %s lost on the way (a gap in their header.seq): a burst larger "
      "than the publisher's queue or the node's (%u)?",
      topic.c_str(), static_cast<unsigned long long>(lost_), publisher.c_str(), kCommandBurst);
  lost_ = 0;
}

void TiltInput::onTilt(const ros::MessageEvent<const marble_maze::BoardTilt>& event) {
  const marble_maze::BoardTilt::ConstPtr& msg = event.getConstMessage();
  checkNoneLost(tilt_topic_, event.getPublisherName(), msg->header);
  if (!std::isfinite(msg->roll) || !std::isfinite(msg->pitch)) {
    MARBLE_MAZE_WARN_WALL_THROTTLE(
        1.0, "%s: refused roll=%s pitch=%s (not finite); the board keeps its tilt",
        tilt_topic_.c_str(), mm::exactText(msg->roll).c_str(), mm::exactText(msg->pitch).c_str());
    refused_();
    return;
  }
  const double limit = limits_().tilt_limit;
  if (std::abs(msg->roll) > limit || std::abs(msg->pitch) > limit)
    MARBLE_MAZE_WARN_WALL_THROTTLE(1.0,
                                   "%s: roll=%g pitch=%g rad beyond tilt_limit %g rad; clamped",
                                   tilt_topic_.c_str(), msg->roll, msg->pitch, limit);
  pass(tilt_topic_, msg->header, mm::TiltCommand::Kind::Angles, msg->roll, msg->pitch);
}

void TiltInput::onTiltRate(const ros::MessageEvent<const marble_maze::BoardTiltRate>& event) {
  const marble_maze::BoardTiltRate::ConstPtr& msg = event.getConstMessage();
  checkNoneLost(rate_topic_, event.getPublisherName(), msg->header);
  if (!std::isfinite(msg->roll_rate) || !std::isfinite(msg->pitch_rate)) {
    MARBLE_MAZE_WARN_WALL_THROTTLE(
        1.0, "%s: refused roll_rate=%s pitch_rate=%s (not finite); nothing changed",
        rate_topic_.c_str(), mm::exactText(msg->roll_rate).c_str(),
        mm::exactText(msg->pitch_rate).c_str());
    refused_();
    return;
  }
  const double limit = limits_().tilt_rate_limit;
  if (limit > 0 && (std::abs(msg->roll_rate) > limit || std::abs(msg->pitch_rate) > limit))
    MARBLE_MAZE_WARN_WALL_THROTTLE(
        1.0, "%s: roll_rate=%g pitch_rate=%g rad/s beyond tilt_rate_limit %g; clamped",
        rate_topic_.c_str(), msg->roll_rate, msg->pitch_rate, limit);
  pass(rate_topic_, msg->header, mm::TiltCommand::Kind::Rates, msg->roll_rate, msg->pitch_rate);
}

void TiltInput::pass(const std::string& topic, const std_msgs::Header& header,
                     mm::TiltCommand::Kind kind, double roll, double pitch) {
  last_ = ros::Time::now();
  ++received_;
  const double held = handler_(header.stamp.isZero() ? last_ : header.stamp, kind, roll, pitch);
  if (held > kHeldWarning)
    MARBLE_MAZE_WARN_WALL_THROTTLE(
        1.0,
        "%s: command stamped %.9f s is held %.6g s, until the simulation's clock "
        "reaches its stamp (stamp commands with ros::Time::now(), which follows "
        "/clock under /use_sim_time, or leave the stamp zero to act at once)",
        topic.c_str(), header.stamp.toSec(), held);
}

void TiltInput::fillHealth(HealthFigures* f) const {
  f->commands = received_;
  f->lost = lost_total_;
  f->since_command = last_.isZero() ? -1 : (ros::Time::now() - last_).toSec();
}

}  // namespace marble_maze_ros
