// tilt_program: plays a tilt program (CSV rows t,roll,pitch) to the board's `tilt` topic on ROS
// time, so that the marble travels with nobody at the controls.
#include <ros/ros.h>

#include "marble_maze/BoardTilt.h"
#include "marble_maze/tilt_schedule.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "tilt_program");
  ros::NodeHandle nh, pnh("~");
  std::string path;
  if (!pnh.getParam("program", path)) {
    ROS_FATAL("%s: required: a CSV file of rows t,roll,pitch", pnh.resolveName("program").c_str());
    return 1;
  }
  const bool loop = pnh.param("loop", true);
  const double rate = pnh.param("rate", 20.0);
  if (!(rate > 0 && rate <= 1000)) {
    ROS_FATAL("%s: expected 0 < rate <= 1000 Hz, got %g", pnh.resolveName("rate").c_str(), rate);
    return 1;
  }
  marble_maze::TiltSchedule program;
  try {
    program = marble_maze::TiltSchedule::load(path);
  } catch (const std::exception& e) {
    ROS_FATAL("%s: %s", pnh.resolveName("program").c_str(), e.what());
    return 1;
  }
  ros::Publisher pub = nh.advertise<marble_maze::BoardTilt>("tilt", 10);
  ros::Time start;
  ros::Rate tick(rate);  // follows ROS time, so /use_sim_time works
  while (ros::ok()) {
    const ros::Time now = ros::Time::now();
    if (!now.isZero()) {
      if (start.isZero()) start = now;
      double t = (now - start).toSec();
      if (loop && program.duration() > 0) t = std::fmod(t, program.duration());
      const auto target = program.at(t);
      marble_maze::BoardTilt msg;
      msg.header.stamp = now;
      msg.roll = target.roll;
      msg.pitch = target.pitch;
      pub.publish(msg);
    }
    ros::spinOnce();
    tick.sleep();
  }
  return 0;
}
