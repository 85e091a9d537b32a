#include "tilt_input.h"

#include <cmath>
#include <cstdio>

#include "marble_maze/params.h"
#include "node_settings.h"
#include "wall_throttle.h"

namespace marble_maze_ros {
namespace mm = marble_maze;

Screened screenCommand(mm::TiltCommand::Kind kind, double roll, double pitch,
                       const mm::Params& limits) {
  const bool angles = kind == mm::TiltCommand::Kind::Angles;
  const char* const roll_field = angles ? "roll" : "roll_rate";
  const char* const pitch_field = angles ? "pitch" : "pitch_rate";
  Screened screened;
  if (!std::isfinite(roll) || !std::isfinite(pitch)) {
    screened.refused = true;
    screened.warning = std::string("refused ") + roll_field + "=" + mm::exactText(roll) + " " +
                       pitch_field + "=" + mm::exactText(pitch) + " (not finite); " +
                       (angles ? "the board keeps its tilt" : "nothing changed");
    return screened;
  }
  // A rate limit of 0 is none.
  const double limit = angles ? limits.tilt_limit : limits.tilt_rate_limit;
  if (limit > 0 && (std::abs(roll) > limit || std::abs(pitch) > limit)) {
    char text[160];
    std::snprintf(text, sizeof text, "%s=%g %s=%g %s beyond %s %g; clamped", roll_field, roll,
                  pitch_field, pitch, angles ? "rad" : "rad/s",
                  angles ? "tilt_limit" : "tilt_rate_limit", limit);
    screened.warning = text;
  }
  return screened;
}

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
  const marble_maze::BoardTilt& msg = *event.getConstMessage();
  take(tilt_topic_, event.getPublisherName(), msg.header, mm::TiltCommand::Kind::Angles, msg.roll,
       msg.pitch);
}

void TiltInput::onTiltRate(const ros::MessageEvent<const marble_maze::BoardTiltRate>& event) {
  const marble_maze::BoardTiltRate& msg = *event.getConstMessage();
  take(rate_topic_, event.getPublisherName(), msg.header, mm::TiltCommand::Kind::Rates,
       msg.roll_rate, msg.pitch_rate);
}

void TiltInput::take(const std::string& topic, const std::string& publisher,
                     const std_msgs::Header& header, mm::TiltCommand::Kind kind, double roll,
                     double pitch) {
  checkNoneLost(topic, publisher, header);
  const Screened screened = screenCommand(kind, roll, pitch, limits_());
  if (screened.refused) {
    MARBLE_MAZE_WARN_WALL_THROTTLE(1.0, "%s: %s", topic.c_str(), screened.warning.c_str());
    refused_();
    return;
  }
  if (!screened.warning.empty())
    MARBLE_MAZE_WARN_WALL_THROTTLE(1.0, "%s: %s", topic.c_str(), screened.warning.c_str());
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
