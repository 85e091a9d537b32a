#include "state_messages.h"

#include <tf2_eigen/tf2_eigen.h>

#include <algorithm>
#include <cstdint>

namespace marble_maze_ros {
namespace mm = marble_maze;

marble_maze::MarbleState marbleStateMessage(const mm::Simulation& sim, const ros::Time& stamp,
                                            const Frames& frames) {
  const mm::Marble& m = sim.marble();
  marble_maze::MarbleState state;
  state.header.stamp = stamp;
  state.header.frame_id = frames.world;
  state.position = tf2::toMsg(sim.worldPosition());
  tf2::toMsg(m.velocity, state.velocity);
  tf2::toMsg(m.angular_velocity, state.angular_velocity);
  state.position_in_board = tf2::toMsg(sim.marbleInBoard());
  state.roll = sim.board().roll();
  state.pitch = sim.board().pitch();
  state.contacts = static_cast<std::uint8_t>(std::min(m.contacts, 255));
  state.in_hole = m.phase == mm::MarblePhase::InHole;
  state.at_goal = m.phase == mm::MarblePhase::AtGoal;
  state.off_board = m.phase == mm::MarblePhase::OffBoard;
  return state;
}

nav_msgs::Odometry odometryMessage(const mm::Simulation& sim, const ros::Time& stamp,
                                   const Frames& frames) {
  const mm::Marble& m = sim.marble();
  nav_msgs::Odometry odom;
  odom.header.stamp = stamp;
  odom.header.frame_id = frames.world;
  odom.child_frame_id = frames.marble;
  odom.pose.pose.position = tf2::toMsg(sim.worldPosition());
  odom.pose.pose.orientation = tf2::toMsg(m.orientation);
  const mm::Mat3 to_marble = m.orientation.toRotationMatrix().transpose();
  tf2::toMsg(mm::Vec3(to_marble * m.velocity), odom.twist.twist.linear);
  tf2::toMsg(mm::Vec3(to_marble * m.angular_velocity), odom.twist.twist.angular);
  return odom;
}

std::array<geometry_msgs::TransformStamped, 2> boardAndMarbleTransforms(const mm::Simulation& sim,
                                                                        const ros::Time& stamp,
                                                                        const Frames& frames) {
  const mm::Mat3& board = sim.board().rotation();
  Eigen::Isometry3d world_to_board = Eigen::Isometry3d::Identity();
  world_to_board.linear() = board;
  world_to_board.translation() = sim.params().board_position;
  geometry_msgs::TransformStamped board_tf = tf2::eigenToTransform(world_to_board);
  board_tf.header.stamp = stamp;
  board_tf.header.frame_id = frames.world;
  board_tf.child_frame_id = frames.board;
  Eigen::Isometry3d board_to_marble = Eigen::Isometry3d::Identity();
  board_to_marble.translation() = sim.marbleInBoard();
  board_to_marble.linear() = board.transpose() * sim.marble().orientation.toRotationMatrix();
  geometry_msgs::TransformStamped marble_tf = tf2::eigenToTransform(board_to_marble);
  marble_tf.header.stamp = stamp;
  marble_tf.header.frame_id = frames.board;
  marble_tf.child_frame_id = frames.marble;
  return {board_tf, marble_tf};
}

}  // namespace marble_maze_ros
