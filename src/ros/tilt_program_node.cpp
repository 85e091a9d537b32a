// tilt_program: plays a tilt program (CSV rows t,roll,pitch) to the board's `tilt` topic on ROS
// time, so that the marble travels with nobody at the controls. Parameters: ~program (the file),
// ~loop (true: start over at its end), ~rate (Hz, 20).
#include <ros/ros.h>

#include <cmath>
#include <stdexcept>

#include "marble_maze/BoardTilt.h"
#include "marble_maze/tilt_schedule.h"
#include "node_settings.h"
#include "run_node.h"

namespace {

class TiltProgramNode {
 public:
  TiltProgramNode(ros::NodeHandle nh, const ros::NodeHandle& pnh) {
    // (A parameter of the wrong type is named, as the other nodes name theirs.)
    const std::string path = marble_maze_ros::readText(pnh, "program", "");
    if (path.empty())
      throw std::runtime_error(pnh.resolveName("program") +
                               ": required: a CSV file of rows t,roll,pitch");
    loop_ = marble_maze_ros::readFlag(pnh, "loop", true);
    const double rate = marble_maze_ros::readNumber(pnh, "rate", 20, 0.1, 1000);
    try {
      program_ = marble_maze::TiltSchedule::load(path);
    } catch (const std::exception& e) {
      throw std::runtime_error(pnh.resolveName("program") + ": " + e.what());
    }
    pub_ = nh.advertise<marble_maze::BoardTilt>("tilt", 10);
    // A timer follows ROS time, so /use_sim_time works.
    timer_ = nh.createTimer(ros::Duration(1.0 / rate), &TiltProgramNode::tick, this);
  }

 private:
  void tick(const ros::TimerEvent&) {
    const ros::Time now = ros::Time::now();
    if (now.isZero()) return;  // no /clock yet
    if (start_.isZero()) start_ = now;
    double t = (now - start_).toSec();
    if (loop_ && program_.duration() > 0) t = std::fmod(t, program_.duration());
    const auto target = program_.at(t);
    marble_maze::BoardTilt msg;
    msg.header.stamp = now;
    msg.roll = target.roll;
    msg.pitch = target.pitch;
    pub_.publish(msg);
  }

  marble_maze::TiltSchedule program_;
  bool loop_ = true;
  ros::Publisher pub_;
  ros::Timer timer_;
  ros::Time start_;
};

}  // namespace

int main(int argc, char** argv) {
  return marble_maze_ros::runNode<TiltProgramNode>(argc, argv, "tilt_program");
}
