// Roots of small polynomials against polynomials built from known roots.
#include <gtest/gtest.h>

#include "marble_maze/polynomial.h"

namespace marble_maze {
namespace {

TEST(Polynomial, QuadraticRootsAscendingWithoutCancellation) {
  // (s - 1e-9)(s - 0.75) = s^2 - (0.75 + 1e-9) s + 7.5e-10: the small root survives.
  const double c[3] = {7.5e-10, -(0.75 + 1e-9), 1};
  double roots[2];
  ASSERT_EQ(signChangesIn(c, 2, 0, 1, roots), 2);
  EXPECT_NEAR(roots[0], 1e-9, 1e-24);
  EXPECT_NEAR(roots[1], 0.75, 1e-15);
}

TEST(Polynomial, QuarticRootsOnAnInterval) {
  // (s - 0.1)(s - 0.3)(s - 0.6)(s - 0.9), expanded.
  const double c[5] = {0.0162, -0.261, 1.17, -1.9, 1};
  double roots[4];
  ASSERT_EQ(signChangesIn(c, 4, 0, 1, roots), 4);
  const double expected[4] = {0.1, 0.3, 0.6, 0.9};
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(roots[k], expected[k], 1e-14) << k;
  ASSERT_EQ(signChangesIn(c, 4, 0.2, 0.7, roots), 2);
  EXPECT_NEAR(roots[0], 0.3, 1e-14);
}

TEST(Polynomial, ADoubleRootTouchesWithoutCrossing) {
  // (s - 0.5)^2 (s^2 + 1): touches zero at 0.5, never below it.
  const double c[5] = {0.25, -1, 1.25, -1, 1};
  double roots[4];
  EXPECT_EQ(signChangesIn(c, 4, 0, 1, roots), 0);
  double s;
  EXPECT_FALSE(firstDescent(c, 4, 0, 1, &s));
}

TEST(Polynomial, FirstDescentSkipsARiseThroughZero) {
  // -(s - 0.2)(s - 0.7): rises through zero at 0.2, falls through it at 0.7.
  const double c[3] = {-0.14, 0.9, -1};
  double s;
  ASSERT_TRUE(firstDescent(c, 2, 0, 1, &s));
  EXPECT_NEAR(s, 0.7, 1e-15);
  EXPECT_FALSE(firstDescent(c, 2, 0, 0.5, &s));
}

}  // namespace
}  // namespace marble_maze
