// Warnings said at most once a period of the wall's clock. rosconsole's ROS_WARN_THROTTLE throttles
// on ROS time, which under a simulated clock may run a thousand times faster than the wall (a
// warning a step) or stand still.
#pragma once

#include <ros/ros.h>

#define MARBLE_MAZE_WARN_WALL_THROTTLE(period, ...)                      \
  do {                                                                   \
    static ::ros::SteadyTime marble_maze_said_;                          \
    const ::ros::SteadyTime marble_maze_now_ = ::ros::SteadyTime::now(); \
    if (marble_maze_said_.isZero() ||                                    \
        (marble_maze_now_ - marble_maze_said_).toSec() >= (period)) {    \
      marble_maze_said_ = marble_maze_now_;                              \
      ROS_WARN(__VA_ARGS__);                                             \
    }                                                                    \
  } while (false)
