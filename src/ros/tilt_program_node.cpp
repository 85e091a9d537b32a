// tilt_program: plays a tilt program (CSV rows t,roll,pitch) to the board's `tilt` topic on ROS
// time, so that the marble travels with nobody at the controls.
#include <ros/ros.h>

#include <stdexcept>

#include "marble_maze/BoardTilt.h"
#include "marble_maze/tilt_schedule.h"
#include "node_settings.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "tilt_program");
  ros::NodeHandle nh, pnh("~");
  std::string path;
  bool loop = true;
  double rate = 20;
  marble_maze::TiltSchedule program;
  try {  // (a parameter of the wrong type is named, as the other nodes name theirs)
    path = marble_maze_ros::readText(pnh, "program", "");
    if (path.empty())
      throw std::runtime_error(pnh.resolveName("program") +
                               ": required: a CSV file of rows t,roll,pitch");
    loop = marble_maze_ros::readFlag(pnh, "loop", loop);
    rate = marble_maze_ros::readNumber(pnh, "rate", rate, 0.1, 1000);
    try {
      program = marble_maze::TiltSchedule::load(path);
    } catch (const std::exception& e) {
      throw std::runtime_error(pnh.resolveName("program") + ": " + e.what());
    }
  } catch (const std::exception& e) {
    ROS_FATAL("%s", e.what());
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
