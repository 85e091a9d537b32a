#include "marble_maze/rotation.h"

#include <cmath>

namespace marble_maze {
namespace {

// Below this squared half angle the series' first left-out terms, x^10 / 10! and x^10 / 11!,
// are under 3e-17 of the terms kept: rounding's size.
constexpr double kSeriesLimit = 0.01;

}  // namespace

Quat turnedBy(const Quat& orientation, const Vec3& rotation) {
  const double x2 = 0.25 * rotation.squaredNorm();  // the half angle, squared
  double cos_half, sin_half_per_angle;              // cos(x) and sin(x) / (2 x)
  if (x2 < kSeriesLimit) {
    cos_half = 1 + x2 * (-1.0 / 2 + x2 * (1.0 / 24 + x2 * (-1.0 / 720 + x2 * (1.0 / 40320))));
    sin_half_per_angle =
        0.5 * (1 + x2 * (-1.0 / 6 + x2 * (1.0 / 120 + x2 * (-1.0 / 5040 + x2 * (1.0 / 362880)))));
  } else {
    const double x = std::sqrt(x2);
    cos_half = std::cos(x);
    sin_half_per_angle = std::sin(x) / (2 * x);
  }
  const Vec3 v = sin_half_per_angle * rotation;
  Quat turned = Quat(cos_half, v.x(), v.y(), v.z()) * orientation;
  // Back to unit length: 1 / sqrt(1 + e) = 1 - e / 2 to within e^2, some 1e-32 for the few
  // rounding errors e that one turn leaves.
  turned.coeffs() *= 0.5 * (3 - turned.coeffs().squaredNorm());
  return turned;
}

}  // namespace marble_maze
