// Small rotations without libm: the board's tilt and the marble's turn in a substep.
#pragma once

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
CosSinc cosSinc(double x2);

/// The unit quaternion `orientation` turned by the rotation vector `rotation` (its direction the
/// axis, its length the angle in rad, world frame), and brought back to unit length.
Quat turnedBy(const Quat& orientation, const Vec3& rotation);

}  // namespace marble_maze
