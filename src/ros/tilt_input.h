// The board's commands from `tilt` (target angles) and `tilt_rate` (rates): refused with a
// warning naming the topic and field when not finite, clamped with a warning beyond the limits,
// and handed on with their stamp (zero: now). A command the handler holds for later (stamped
// ahead of the simulation's clock) is told at once, with how far ahead; commands lost on the way
// (a gap in a publisher's header.seq: its queue overflowed) are told once the gap is sure (see
// SeqGaps). Counts them, for the diagnostics.
#pragma once

#include <ros/ros.h>

#include <cstdint>
#include <functional>
#include <string>

#include "health.h"
#include "marble_maze/BoardTilt.h"
#include "marble_maze/BoardTiltRate.h"
#include "marble_maze/params.h"
#include "marble_maze/session.h"
#include "seq_gaps.h"

namespace marble_maze_ros {

/// What a command's values call for: `refused` when not finite (nothing changes), `warning` when
/// beyond the limit in force (the core clamps it) or refused. The warning names the fields; the
/// caller puts the topic before it.
struct Screened {
  bool refused = false;
  std::string warning;
};
Screened screenCommand(marble_maze::TiltCommand::Kind kind, double roll, double pitch,
                       const marble_maze::Params& limits);

class TiltInput {
 public:
  /// Takes a command; returns how long (s of the simulation's time) it is held before it acts.
  using Handler = std::function<double(const ros::Time& stamp, marble_maze::TiltCommand::Kind kind,
                                       double roll, double pitch)>;
  /// Held longer than this, a command is warned about (throttled): a stamp of wall time into a
  /// node on simulated time, a clock that jumped back.
  static constexpr double kHeldWarning = 0.1;  // s
  /// `limits` gives the tilt and rate limits in force (they may change while running);
  /// `refused` is called after a command is refused (not finite), so that a loop waiting for
  /// the answer to each command gets one.
  TiltInput(ros::NodeHandle& nh, Handler handler,
            std::function<const marble_maze::Params&()> limits, std::function<void()> refused);

  /// The commands' figures of /diagnostics: received since the start, lost on the way (gaps in
  /// their publishers' header.seq), seconds of ROS time since the last.
  void fillHealth(HealthFigures* figures) const;

 private:
  void onTilt(const ros::MessageEvent<const marble_maze::BoardTilt>& event);
  void onTiltRate(const ros::MessageEvent<const marble_maze::BoardTiltRate>& event);
  /// Counts and warns about the commands that `header`'s seq shows lost (see SeqGaps).
  void checkNoneLost(const std::string& topic, const std::string& publisher,
                     const std_msgs::Header& header);
  /// Screens a command and, unless refused, hands it on.
  void take(const std::string& topic, const std::string& publisher, const std_msgs::Header& header,
            marble_maze::TiltCommand::Kind kind, double roll, double pitch);

  Handler handler_;
  std::function<const marble_maze::Params&()> limits_;
  std::function<void()> refused_;
  ros::Subscriber tilt_sub_, rate_sub_;
  std::string tilt_topic_, rate_topic_;  // kept: a warning names them long after subscribing
  std::uint64_t received_ = 0;
  ros::Time last_;
  SeqGaps gaps_;
  std::uint64_t lost_ = 0;  // commands lost since the last warning
  std::uint64_t lost_total_ = 0;
  ros::WallTime said_lost_;
};

}  // namespace marble_maze_ros
