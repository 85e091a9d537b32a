#include "marble_maze/polynomial.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace marble_maze {
namespace {

constexpr int kMaxDegree = 4;

/// The root of a polynomial that is monotonic on [a, b] and changes sign there: Newton's method,
/// falling back to bisection whenever a Newton step leaves the bracket.
double refine(const double* c, int degree, double a, double b) {
  double fa = evaluatePolynomial(c, degree, a);
  double derivative[kMaxDegree];
  for (int k = 1; k <= degree; ++k) derivative[k - 1] = k * c[k];
  double x = 0.5 * (a + b);
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double fx = evaluatePolynomial(c, degree, x);
    if (fx == 0) return x;
    if ((fx > 0) == (fa > 0)) {
      a = x;
      fa = fx;
    } else {
      b = x;
    }
    const double slope = evaluatePolynomial(derivative, degree - 1, x);
    double next = slope != 0 ? x - fx / slope : a;
    if (!(next > a && next < b)) next = 0.5 * (a + b);
    if (next == x ||
        b - a <= 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(x)))
      return next;
    x = next;
  }
  return x;
}

}  // namespace

double evaluatePolynomial(const double* c, int degree, double s) {
  double value = c[degree];
  for (int k = degree - 1; k >= 0; --k) value = value * s + c[k];
  return value;
}

int signChangesIn(const double* c, int degree, double lo, double hi, double* roots) {
  while (degree > 0 && c[degree] == 0) --degree;
  if (degree <= 0) return 0;
  int count = 0;
  const auto keep = [&](double s) {
    if (s >= lo && s <= hi) roots[count++] = s;
  };
  if (degree == 1) {
    keep(-c[0] / c[1]);
    return count;
  }
  if (degree == 2) {
    const double disc = c[1] * c[1] - 4 * c[2] * c[0];
    if (disc <= 0) return 0;  // no root, or a double one that does not cross zero
    // The stable pair: no cancellation between -b and the square root.
    const double q = -0.5 * (c[1] + std::copysign(std::sqrt(disc), c[1]));
    double r1 = q / c[2], r2 = q != 0 ? c[0] / q : r1;
    if (r1 > r2) std::swap(r1, r2);
    keep(r1);
    keep(r2);
    return count;
  }
  // Higher degrees: between the derivative's sign changes the polynomial is monotonic, so each
  // piece holds at most one sign change.
  double derivative[kMaxDegree];
  for (int k = 1; k <= degree; ++k) derivative[k - 1] = k * c[k];
  double bounds[kMaxDegree + 1];  // lo, the turns, hi
  bounds[0] = lo;
  const int turns = signChangesIn(derivative, degree - 1, lo, hi, bounds + 1);
  bounds[turns + 1] = hi;
  double values[kMaxDegree + 1];
  for (int k = 0; k <= turns + 1; ++k) values[k] = evaluatePolynomial(c, degree, bounds[k]);
  for (int k = 0; k <= turns + 1; ++k) {
    // A zero at an end of the interval counts; at a turn only where the sign changes across it.
    if (values[k] == 0 &&
        (k == 0 || k == turns + 1 ||
         (values[k - 1] != 0 && values[k + 1] != 0 && (values[k - 1] > 0) != (values[k + 1] > 0))))
      roots[count++] = bounds[k];
    if (k <= turns && values[k] != 0 && values[k + 1] != 0 &&
        (values[k] > 0) != (values[k + 1] > 0))
      roots[count++] = refine(c, degree, bounds[k], bounds[k + 1]);
  }
  return count;
}

bool firstDescent(const double* c, int degree, double lo, double hi, double* s) {
  double roots[kMaxDegree];
  const int count = signChangesIn(c, degree, lo, hi, roots);
  for (int k = 0; k < count; ++k) {
    if (roots[k] <= lo) continue;
    // Going down through zero: just before the root the polynomial is positive.
    const double before =
        evaluatePolynomial(c, degree, 0.5 * (roots[k] + (k > 0 ? std::max(lo, roots[k - 1]) : lo)));
    if (before > 0) {
      *s = roots[k];
      return true;
    }
  }
  return false;
}

}  // namespace marble_maze
