// The board's commands from `tilt` (target angles) and `tilt_rate` (rates): refused with a
// warning naming the topic and field when not finite, clamped with a warning beyond the limits,
// and handed on with their stamp (zero: now). Counts them, for the diagnostics.
#pragma once

#include <ros/ros.h>

#include <cstdint>
#include <functional>
#include <string>

#include "marble_maze/BoardTilt.h"
#include "marble_maze/BoardTiltRate.h"
#include "marble_maze/params.h"
#include "marble_maze/session.h"

namespace marble_maze_ros {

class TiltInput {
 public:
  using Handler = std::function<void(const ros::Time& stamp, marble_maze::TiltCommand::Kind kind,
                                     double roll, double pitch)>;
  /// `limits` gives the tilt and rate limits in force (they may change while running).
  TiltInput(ros::NodeHandle& nh, Handler handler,
            std::function<const marble_maze::Params&()> limits);

  std::uint64_t received() const { return received_; }
  ros::Time last() const { return last_; }

 private:
  void onTilt(const marble_maze::BoardTilt::ConstPtr& msg);
  void onTiltRate(const marble_maze::BoardTiltRate::ConstPtr& msg);
  void pass(const std_msgs::Header& header, marble_maze::TiltCommand::Kind kind, double roll,
            double pitch);

  Handler handler_;
  std::function<const marble_maze::Params&()> limits_;
  ros::Subscriber tilt_sub_, rate_sub_;
  std::string tilt_topic_, rate_topic_;  // kept: a warning names them long after subscribing
  std::uint64_t received_ = 0;
  ros::Time last_;
};

}  // namespace marble_maze_ros
