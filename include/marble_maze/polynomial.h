// Real roots of small polynomials on an interval, for the times of impact along a curved path:
// a path p(s) = from + path s + bend s^2 meets a plane at a root of a quadratic, and a rounded
// edge or corner at a root of a quartic.
#pragma once

namespace marble_maze {

/// The polynomial c[0] + c[1] s + ... + c[degree] s^degree at s.
double evaluatePolynomial(const double* c, int degree, double s);

/// The roots in [lo, hi] at which the polynomial changes sign, ascending, into roots (room for
/// `degree` of them); returns how many. Each is found to within a few units of the last place.
/// Roots of even multiplicity (touching zero without crossing it) are not reported.
int signChangesIn(const double* c, int degree, double lo, double hi, double* roots);

/// The first s in (lo, hi] at which the polynomial goes from positive to negative; false if none.
bool firstDescent(const double* c, int degree, double lo, double hi, double* s);

}  // namespace marble_maze
