// Drives the marble to a point of the board (~x, ~y, m) and holds it there: a closed loop over
// marble_state and tilt, the smallest controller that works. A rolling marble speeds up at
// (5/7) g sin(tilt) down the slope: positive pitch lowers the board's +x edge, positive roll
// raises its +y edge.
#include <ros/ros.h>

#include <algorithm>
#include <cmath>

#include "marble_maze/BoardTilt.h"
#include "marble_maze/MarbleState.h"

constexpr double kP = 4.0, kD = 3.0;             // 1/s^2, 1/s: acceleration per metre off, per m/s
constexpr double kLimit = 0.17;                  // rad, within the board's tilt limit
constexpr double kPerRadian = 5.0 / 7.0 * 9.81;  // m/s^2 per unit sin(tilt)

double tiltFor(double acceleration) {
  return std::clamp(std::asin(std::clamp(acceleration / kPerRadian, -1.0, 1.0)), -kLimit, kLimit);
}

int main(int argc, char** argv) {
  ros::init(argc, argv, "drive_to_point");
  ros::NodeHandle nh, pnh("~");
  const double x = pnh.param("x", 0.0), y = pnh.param("y", 0.0);
  ros::Publisher tilt = nh.advertise<marble_maze::BoardTilt>("tilt", 1);
  ros::Subscriber state = nh.subscribe<marble_maze::MarbleState>(
      "marble_state", 1, [&](const marble_maze::MarbleState::ConstPtr& s) {
        marble_maze::BoardTilt command;
        command.header.stamp = ros::Time::now();
        command.pitch = tiltFor(kP * (x - s->position_in_board.x) - kD * s->velocity.x);
        command.roll = -tiltFor(kP * (y - s->position_in_board.y) - kD * s->velocity.y);
        tilt.publish(command);
      });
  ros::spin();
}
