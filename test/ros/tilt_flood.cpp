// A tilt publisher gone wild, for flood.test: waits until its ~start parameter is true, then
// publishes `tilt` at ~rate (10 kHz) for ~duration (10 s) of wall time, each command stamped
// now and numbered in its roll (command k: k * 1e-7 rad, so that the order of those the node
// applies can be checked), and then sets ~sent (how many) and ~done, says so, and ends.
#include <ros/ros.h>

#include <cstdint>

#include "marble_maze/BoardTilt.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "tilt_flood");
  ros::NodeHandle nh, pnh("~");
  const double rate = pnh.param("rate", 10000.0);
  const double duration = pnh.param("duration", 10.0);
  ros::Publisher tilt = nh.advertise<marble_maze::BoardTilt>("tilt", 1000);
  while (ros::ok() && !pnh.param("start", false)) ros::WallDuration(0.02).sleep();
  const ros::WallTime begin = ros::WallTime::now();
  std::uint64_t sent = 0;
  for (;;) {
    const double elapsed = (ros::WallTime::now() - begin).toSec();
    if (!ros::ok() || elapsed >= duration) break;
    for (const auto due = static_cast<std::uint64_t>(elapsed * rate); sent < due; ++sent) {
      marble_maze::BoardTilt command;
      command.header.stamp = ros::Time::now();
      command.roll = static_cast<double>(sent + 1) * 1e-7;
      tilt.publish(command);
    }
    ros::WallDuration(0.0002).sleep();
  }
  pnh.setParam("sent", static_cast<int>(sent));
  pnh.setParam("done", true);
  ROS_INFO("tilt_flood: sent %llu tilt commands in %g s", static_cast<unsigned long long>(sent),
           duration);
  // A moment for the commands still queued to go out (the publisher's queue, up to 1,000 of
  // them, goes with the node), then done: a flood run by hand ends by itself.
  ros::WallDuration(1.0).sleep();
  return 0;
}
