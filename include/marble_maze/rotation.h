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

/// cos(x) and sin(x) / x from x^2. Up to x = 0.25 rad (a board's tilt, a substep's turn of the
/// marble) by their series, exact to rounding there, which take no square root, no division and
/// no libm call, and wait on a short chain of products; beyond, by std::cos and std::sin.
/// (Inline: it runs three times a substep.)
inline CosSinc cosSinc(double x2) {
  // Up to x = 0.25 rad the first terms the series leave out, x^14 / 14! of cos and x^12 / 13!
  // of sin(x) / x, are below 1e-17: rounding's size.
  constexpr double kSeriesLimit = 0.0625;  // x^2
  if (!(x2 <= kSeriesLimit)) {
    const double x = std::sqrt(x2);
    return {std::cos(x), std::sin(x) / x};
  }
  // Estrin's scheme: the powers x^4 and x^8 are worked out alongside the pairs of terms, a short
  // chain to wait on.
  const double x4 = x2 * x2, x8 = x4 * x4;
  const double cos = (1 - 0.5 * x2) + x4 * (1.0 / 24 - x2 * (1.0 / 720)) +
                     x8 * ((1.0 / 40320 - x2 * (1.0 / 3628800)) + x4 * (1.0 / 479001600));
  const double sinc = (1 - x2 * (1.0 / 6)) + x4 * (1.0 / 120 - x2 * (1.0 / 5040)) +
                      x8 * (1.0 / 362880 - x2 * (1.0 / 39916800));
  return {cos, sinc};
}

/// The unit quaternion `orientation` turned by the rotation vector `rotation` (its direction the
/// axis, its length the angle in rad, world frame), and brought back to unit length.
Quat turnedBy(const Quat& orientation, const Vec3& rotation);

}  // namespace marble_maze
