// Vector types and the axis-aligned box shared by the physics core.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace marble_maze {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;
using Index3 = Eigen::Vector3i;

/// An axis-aligned box, given by its lower and upper corners.
struct Box {
  Vec3 lower;
  Vec3 upper;

  Vec3 centre() const { return 0.5 * (lower + upper); }
  Vec3 size() const { return upper - lower; }
};

}  // namespace marble_maze
