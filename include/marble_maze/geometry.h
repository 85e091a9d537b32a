// Vector types, a marble's velocities and the axis-aligned box shared by the physics core.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <cstring>

namespace marble_maze {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;
using Index3 = Eigen::Vector3i;

constexpr double kPi = 3.14159265358979323846;
/// The most a board tilts either way (rad): the bound of tilt_limit and of every tilt.
constexpr double kQuarterTurn = kPi / 2;

/// A value's bits.
inline std::uint64_t bitsOf(double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}
/// Whether two values are the same to the last bit: 0 and -0 differ, a NaN is itself.
inline bool sameBits(double a, double b) {
  return bitsOf(a) == bitsOf(b);
}
inline bool sameBits(const Vec3& a, const Vec3& b) {
  return sameBits(a.x(), b.x()) && sameBits(a.y(), b.y()) && sameBits(a.z(), b.z());
}
inline bool sameBits(const Quat& a, const Quat& b) {
  return sameBits(a.w(), b.w()) && sameBits(a.vec(), b.vec());
}

/// a x b, the same to the bit as Eigen's cross(), with its x and y worked out as one pair: the
/// step stores cross products and soon reads them back, x and y together, which waits long when
/// they were stored apart (the processor cannot forward two stores to one load).
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  const Eigen::Vector2d xy =
      Eigen::Vector2d(a.y(), a.z()).cwiseProduct(Eigen::Vector2d(b.z(), b.x())) -
      Eigen::Vector2d(a.z(), a.x()).cwiseProduct(Eigen::Vector2d(b.y(), b.z()));
  return Vec3(xy.x(), xy.y(), a.x() * b.y() - a.y() * b.x());
}

/// m v, the same to the bit as Eigen's product, reading m an entry at a time: a matrix just put
/// together an entry at a time (a rotation from its angles) and read back in pairs, as Eigen's
/// product reads its columns, waits for its writes to land. (Eigen sums rows 0 and 1, a pair,
/// from their first term on, and row 2 as its first term plus the sum of the other two.) To the
/// bit only where no FMA fuses a product into a sum, as in the package's x86-64 build: built for
/// a processor with FMA (-march=native), Eigen fuses and this may not.
inline Vec3 product(const Mat3& m, const Vec3& v) {
  return Vec3((m(0, 0) * v.x() + m(0, 1) * v.y()) + m(0, 2) * v.z(),
              (m(1, 0) * v.x() + m(1, 1) * v.y()) + m(1, 2) * v.z(),
              m(2, 0) * v.x() + (m(2, 1) * v.y() + m(2, 2) * v.z()));
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
