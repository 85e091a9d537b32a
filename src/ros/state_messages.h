// The marble's state as ROS messages: `marble_state`, `odom` and the tf pair world -> board ->
// marble, built from a simulation at a stamp (REP 103 axes, REP 105 frames named by the caller).
#pragma once

#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/time.h>

#include <array>
#include <string>

#include "frames.h"
#include "marble_maze/MarbleState.h"
#include "marble_maze/simulation.h"

namespace marble_maze_ros {

/// Position and velocities in the world frame, the position in the board's too, the tilt, the
/// contacts and the phase.
marble_maze::MarbleState marbleStateMessage(const marble_maze::Simulation& sim,
                                            const ros::Time& stamp, const Frames& frames);
/// The pose in the world frame, the twist in the marble's own frame (REP 105's odometry).
nav_msgs::Odometry odometryMessage(const marble_maze::Simulation& sim, const ros::Time& stamp,
                                   const Frames& frames);
/// world -> board (the tilt, at the board's position) and board -> marble.
std::array<geometry_msgs::TransformStamped, 2> boardAndMarbleTransforms(
    const marble_maze::Simulation& sim, const ros::Time& stamp, const Frames& frames);

}  // namespace marble_maze_ros
