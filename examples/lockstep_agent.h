// A roscpp agent in lockstep, as a class any process can hold: beside a node started with
// ~lockstep, it waits `settle` seconds (default 0.5) once the two see each other, sends `periods`
// tilt commands (a circling tilt; default 5000), each as the state answering the one before
// arrives, then prints the periods a second of wall time and the CPU its process spent a period,
// and stops. It reads `settle` and `periods` under the handle it is given for them.
// The agent's nodelet (lockstep_agent_nodelet.cpp) and the node and agent in one process on one
// thread (lockstep_in_process.cpp) hold one each.
#pragma once

#include <ros/ros.h>
#include <time.h>

#include <boost/make_shared.hpp>
#include <cmath>
#include <cstdio>

#include "marble_maze/BoardTilt.h"
#include "marble_maze/MarbleState.h"

namespace marble_maze_examples {

class LockstepAgent {
 public:
  /// Topics under `nh`, `periods` and `settle` under `settings`.
  LockstepAgent(ros::NodeHandle nh, const ros::NodeHandle& settings)
      : periods_(settings.param("periods", 5000)), settle_(settings.param("settle", 0.5)) {
    tilt_ = nh.advertise<marble_maze::BoardTilt>("tilt", 10);
    state_ = nh.subscribe("marble_state", 10, &LockstepAgent::answered, this);
    wait_ = nh.createWallTimer(ros::WallDuration(0.01), &LockstepAgent::start, this);
  }

 private:
  /// Once the node and the agent see each other, and ~settle later (every link made, and a
  /// listener started meanwhile sees the whole run), the first command.
  void start(const ros::WallTimerEvent&) {
    if (tilt_.getNumSubscribers() == 0 || state_.getNumPublishers() == 0) return;
    if (connected_.isZero()) connected_ = ros::WallTime::now();
    if (ros::WallTime::now() - connected_ < settle_) return;
    wait_.stop();
    begin_ = ros::WallTime::now();
    cpu_before_ = processCpuSeconds();
    command();
  }

  void answered(const marble_maze::MarbleState::ConstPtr& state) {
    if (begin_.isZero() || done_ == periods_ || state->header.stamp <= last_)
      return;  // (not the answer to a command)
    last_ = state->header.stamp;
    if (++done_ < periods_) return command();
    const double wall = (ros::WallTime::now() - begin_).toSec();
    const double cpu = processCpuSeconds() - cpu_before_;
    std::printf("%d periods in %.3f s: %.0f periods/s; the process's CPU %.1f us a period\n", done_,
                wall, done_ / wall, 1e6 * cpu / done_);
    std::fflush(stdout);
  }

  void command() {
    // (A shared message: a node in the same process takes it without a copy or a wake of
    // roscpp's poll thread.)
    auto tilt = boost::make_shared<marble_maze::BoardTilt>();
    tilt->roll = 0.05 * std::cos(done_ * 0.01);
    tilt->pitch = 0.05 * std::sin(done_ * 0.01);
    tilt_.publish(tilt);
  }

  static double processCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
  }

  ros::Publisher tilt_;
  ros::Subscriber state_;
  ros::WallTimer wait_;
  ros::WallTime connected_, begin_;
  ros::Time last_;
  int periods_ = 0, done_ = 0;
  ros::WallDuration settle_;
  double cpu_before_ = 0;
};

}  // namespace marble_maze_examples
