// Vector types, a marble's velocities and the axis-aligned box shared by the physics core.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace marble_maze {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;
using Index3 = Eigen::Vector3i;

constexpr double kPi = 3.14159265358979323846;
/// The most a board tilts either way (rad): the bound of tilt_limit and of every tilt.
constexpr double kQuarterTurn = kPi / 2;

/// a x b, the same to the bit as Eigen's cross(), with its x and y worked out as one pair: the
/// step stores cross products and soon reads them back, x and y together, which waits long when
/// they were stored apart (the processor cannot forward two stores to one load).
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  const Eigen::Vector2d xy =
      Eigen::Vector2d(a.y(), a.z()).cwiseProduct(Eigen::Vector2d(b.z(), b.x())) -
      Eigen::Vector2d(a.z(), a.x()).cwiseProduct(Eigen::Vector2d(b.y(), b.z()));
  return Vec3(xy.x(), xy.y(), a.x() * b.y() - a.y() * b.x());
}

/// A marble's linear and angular velocity (world frame), as the integrators advance them and the
/// contact solver changes them (its mass, inertia and radius are the params').
struct Velocities {
  Vec3 linear = Vec3::Zero();
  Vec3 angular = Vec3::Zero();
};

/// An axis-aligned box, given by its lower and upper corners.
struct Box {
  Vec3 lower;
  Vec3 upper;

  Vec3 centre() const { return 0.5 * (lower + upper); }
  Vec3 size() const { return upper - lower; }
};

}  // namespace marble_maze
