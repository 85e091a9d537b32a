#include "marble_maze/rotation.h"

#include <cmath>

namespace marble_maze {

Quat turnedBy(const Quat& orientation, const Vec3& rotation) {
  const CosSinc half = cosSinc(0.25 * rotation.squaredNorm());  // of half the angle
  const Vec3 v = 0.5 * half.sinc * rotation;                    // sin(angle / 2) along the axis
  Quat turned = Quat(half.cos, v.x(), v.y(), v.z()) * orientation;
  // Back to unit length: 1 / sqrt(1 + e) = 1 - e / 2 to within e^2, some 1e-32 for the few
  // rounding errors e that one turn leaves.
  turned.coeffs() *= 0.5 * (3 - turned.coeffs().squaredNorm());
  return turned;
}

}  // namespace marble_maze
