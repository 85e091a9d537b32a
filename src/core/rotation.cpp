#include "marble_maze/rotation.h"

#include <cmath>

namespace marble_maze {
namespace {

// Up to x = 0.25 rad the first terms the series leave out, x^14 / 14! of cos and x^12 / 13! of
// sin(x) / x, are below 1e-17: rounding's size.
constexpr double kSeriesLimit = 0.0625;  // x^2

}  // namespace

CosSinc cosSinc(double x2) {
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
