// Small rotations without libm: the board's tilt and the marble's turn in a substep.
#pragma once

#include <cmath>

#include "marble_maze/geometry.h"

namespace marble_maze {

/// cos(x) and sin(x) / x.
struct CosSinc {
  double cos;
  double sinc;
};

namespace series {

// Up to x = 0.25 rad the first terms the series of cos(x) and sin(x) / x leave out, x^14 / 14!
// and x^12 / 13!, are below 1e-17: rounding's size.
constexpr double kLimit = 0.0625;  // x^2
// Their terms' factors, of x^0, x^2, ... x^12: (-1)^k / (2k)! and (-1)^k / (2k + 1)!, the sign
// taken by the scheme below (sin(x) / x has no x^12 term within rounding: a zero).
constexpr double kCos[7] = {1,           1.0 / 2,       1.0 / 24,       1.0 / 720,
                            1.0 / 40320, 1.0 / 3628800, 1.0 / 479001600};
constexpr double kSinc[7] = {1, 1.0 / 6, 1.0 / 120, 1.0 / 5040, 1.0 / 362880, 1.0 / 39916800, 0};

/// Estrin's scheme in each lane, from x^2 and the lane's factors: the powers x^4 and x^8 are
/// worked out alongside the pairs of terms, a short chain to wait on. Every lane takes the same
/// operations in the same order, so a series is the same to the bit in any lane (a factor of 0
/// adds a zero), and two take the instructions of one.
inline Eigen::Array2d estrin(const Eigen::Array2d& x2, const Eigen::Array2d* f) {
  const Eigen::Array2d x4 = x2 * x2, x8 = x4 * x4;
  return (f[0] - x2 * f[1]) + x4 * (f[2] - x2 * f[3]) + x8 * ((f[4] - x2 * f[5]) + x4 * f[6]);
}

}  // namespace series

/// cos(x) and sin(x) / x from x^2. Up to x = 0.25 rad (a board's tilt, a substep's turn of the
/// marble) by their series, exact to rounding there, which take no square root, no division and
/// no libm call, and wait on a short chain of products; beyond, by std::cos and std::sin.
/// (Inline: it runs three times a substep.)
inline CosSinc cosSinc(double x2) {
  if (!(x2 <= series::kLimit)) {
    const double x = std::sqrt(x2);
    return {std::cos(x), std::sin(x) / x};
  }
  // The two series side by side: cos in the first lane, sin(x) / x in the second.
  Eigen::Array2d f[7];
  for (int k = 0; k < 7; ++k) f[k] = Eigen::Array2d(series::kCos[k], series::kSinc[k]);
  const Eigen::Array2d both = series::estrin(Eigen::Array2d::Constant(x2), f);
  return {both[0], both[1]};
}

/// cosSinc of two angles from their squares, each to the bit as cosSinc gives it, in about the
/// instructions of one: a board's roll and pitch.
inline void cosSinc(double a2, double b2, CosSinc* a, CosSinc* b) {
  if (!(a2 <= series::kLimit && b2 <= series::kLimit)) {
    *a = cosSinc(a2);
    *b = cosSinc(b2);
    return;
  }
  Eigen::Array2d cos_f[7], sinc_f[7];
  for (int k = 0; k < 7; ++k) {
    cos_f[k] = Eigen::Array2d::Constant(series::kCos[k]);
    sinc_f[k] = Eigen::Array2d::Constant(series::kSinc[k]);
  }
  const Eigen::Array2d x2(a2, b2);
  const Eigen::Array2d cos = series::estrin(x2, cos_f), sinc = series::estrin(x2, sinc_f);
  *a = {cos[0], sinc[0]};
  *b = {cos[1], sinc[1]};
}

/// The unit quaternion `orientation` turned by the rotation vector `rotation` (its direction the
/// axis, its length the angle in rad, world frame), and brought back to unit length. (Inline,
/// always: called, it ran 4 ns slower a substep, 2.5% of a rolling step, its quaternion written
/// to memory and read back.)
[[gnu::always_inline]] inline Quat turnedBy(const Quat& orientation, const Vec3& rotation) {
  const CosSinc half = cosSinc(0.25 * rotation.squaredNorm());  // of half the angle
  const Vec3 v = 0.5 * half.sinc * rotation;                    // sin(angle / 2) along the axis
  Quat turned = Quat(half.cos, v.x(), v.y(), v.z()) * orientation;
  // Back to unit length: 1 / sqrt(1 + e) = 1 - e / 2 to within e^2, some 1e-32 for the few
  // rounding errors e that one turn leaves.
  turned.coeffs() *= 0.5 * (3 - turned.coeffs().squaredNorm());
  return turned;
}

}  // namespace marble_maze
