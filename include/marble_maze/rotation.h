// Turning an orientation by a rotation vector, as each substep does to the rolling marble's.
#pragma once

#include "marble_maze/geometry.h"

namespace marble_maze {

/// The unit quaternion `orientation` turned by the rotation vector `rotation` (its direction the
/// axis, its length the angle in rad, world frame), and brought back to unit length. A substep's
/// turn is small (some 0.1 rad): its quaternion then comes from the series of cos and sin / x in
/// the squared half angle, which take no square root, no division and no libm call, and are
/// exact to rounding below a half angle of 0.1 rad; larger turns take cos and sin.
Quat turnedBy(const Quat& orientation, const Vec3& rotation);

}  // namespace marble_maze
