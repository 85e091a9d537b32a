#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "marble_maze/board.h"
#include "marble_maze/rotation.h"

namespace marble_maze {
namespace {

TEST(CosSinc, MatchesTheLibraryToRoundingOnBothSidesOfTheSeries) {
  // cos(x) and sin(x) / x from x^2, for x from 0 to 1 rad: the series up to 0.25 rad, std::cos
  // and std::sin beyond, within a rounding of std::cos (1.2e-16) and two of std::sin(x) / x, and
  // no step where the one gives way to the other.
  for (int n = 0; n <= 100000; ++n) {
    const double x = 1e-5 * n;
    const CosSinc c = cosSinc(x * x);
    ASSERT_NEAR(c.cos, std::cos(x), 1.2e-16) << "x " << x;
    ASSERT_NEAR(c.sinc, n == 0 ? 1.0 : std::sin(x) / x, 2.3e-16) << "x " << x;
  }
  const double below = std::nextafter(0.25, 0.0), above = std::nextafter(0.25, 1.0);
  EXPECT_NEAR(cosSinc(below * below).cos, cosSinc(above * above).cos, 3e-16);
  EXPECT_NEAR(cosSinc(below * below).sinc, cosSinc(above * above).sinc, 3e-16);
}

TEST(CosSinc, LanesGiveTheScalarSeriesToTheBit) {
  // The series worked out in SSE2's two lanes (cos and sin(x) / x of one angle side by side, and
  // roll's and pitch's side by side) give, bit for bit, what the scalar Estrin scheme below gave
  // before them, for angles of either sign up to the series' end (0.25 rad): the simulation's
  // trajectories stand on it.
  const auto scalar = [](double x2) {
    const double x4 = x2 * x2, x8 = x4 * x4;
    const double cos = (1 - 0.5 * x2) + x4 * (1.0 / 24 - x2 * (1.0 / 720)) +
                       x8 * ((1.0 / 40320 - x2 * (1.0 / 3628800)) + x4 * (1.0 / 479001600));
    const double sinc = (1 - x2 * (1.0 / 6)) + x4 * (1.0 / 120 - x2 * (1.0 / 5040)) +
                        x8 * (1.0 / 362880 - x2 * (1.0 / 39916800));
    return CosSinc{cos, sinc};
  };
  std::mt19937 random(5);
  std::uniform_real_distribution<double> angle(-0.25, 0.25);
  for (int n = 0; n < 200000; ++n) {
    const double a = n == 0 ? 0.0 : n == 1 ? 0.25 : angle(random), b = angle(random);
    const CosSinc expected_a = scalar(a * a), expected_b = scalar(b * b);
    const CosSinc one = cosSinc(a * a);
    CosSinc pa, pb;
    cosSinc(a * a, b * b, &pa, &pb);
    ASSERT_EQ(one.cos, expected_a.cos) << "x " << a;
    ASSERT_EQ(one.sinc, expected_a.sinc) << "x " << a;
    ASSERT_EQ(pa.cos, expected_a.cos) << "roll " << a;
    ASSERT_EQ(pa.sinc, expected_a.sinc) << "roll " << a;
    ASSERT_EQ(pb.cos, expected_b.cos) << "pitch " << b;
    ASSERT_EQ(pb.sinc, expected_b.sinc) << "pitch " << b;
  }
  // Beyond the series in either lane, both angles are each alone's.
  CosSinc pa, pb;
  cosSinc(0.09, 0.01, &pa, &pb);
  EXPECT_EQ(pa.cos, cosSinc(0.09).cos);
  EXPECT_EQ(pb.sinc, scalar(0.01).sinc);
}

TEST(Geometry, ProductAndCrossGiveEigensToTheBit) {
  // product() and cross() read and pair their operands to spare the step a wait, and must give
  // what Eigen's m * v and a.cross(b) give, bit for bit (the trajectories stand on it), rotations
  // and other matrices alike, with zeros of either sign among the entries.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> entry(-1, 1);
  const auto value = [&](int n, int k) {
    const int kind = (n + 3 * k) % 11;
    return kind == 0 ? 0.0 : kind == 1 ? -0.0 : entry(random);
  };
  for (int n = 0; n < 200000; ++n) {
    Mat3 m;
    if (n % 2 == 0) {
      m = Board::rotationFor(0.3 * entry(random), 0.3 * entry(random));
    } else {
      for (int k = 0; k < 9; ++k) m.data()[k] = value(n, k);
    }
    const Vec3 v(value(n, 9), value(n, 10), value(n, 11));
    const Vec3 w(entry(random), value(n, 12), entry(random));
    const Vec3 by_eigen = m * v, ours = product(m, v);
    for (int a = 0; a < 3; ++a) {
      ASSERT_EQ(std::signbit(ours[a]), std::signbit(by_eigen[a])) << "row " << a << " at " << n;
      ASSERT_EQ(ours[a], by_eigen[a]) << "row " << a << " at " << n;
    }
    const Vec3 cross_eigen = v.cross(w), ours_cross = cross(v, w);
    for (int a = 0; a < 3; ++a) {
      ASSERT_EQ(std::signbit(ours_cross[a]), std::signbit(cross_eigen[a])) << a << " at " << n;
      ASSERT_EQ(ours_cross[a], cross_eigen[a]) << a << " at " << n;
    }
  }
}

TEST(TurnedBy, MatchesTheAngleAxisQuaternionFromTinyToLargeTurns) {
  // Rotation vectors of every length from 1e-12 to 3 rad, on both sides of where the series
  // gives way to cos and sin (a turn of 0.5 rad): the turned orientation is Eigen's angle-axis
  // product, normalised, to within a few roundings (1e-15) in each coefficient.
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(-1, 1), exponent(-12, std::log10(3.0));
  Quat q(Eigen::AngleAxisd(0.7, Vec3(1, -2, 3).normalized()));
  for (int n = 0; n < 100000; ++n) {
    const Vec3 axis = Vec3(unit(random), unit(random), unit(random)).normalized();
    const double angle =
        n % 10 == 0 ? 0.2 * (1 + 1e-3 * unit(random)) : std::pow(10, exponent(random));
    const Vec3 rotation = angle * axis;
    const Quat expected = (Quat(Eigen::AngleAxisd(angle, axis)) * q).normalized();
    const Quat turned = turnedBy(q, rotation);
    ASSERT_LT((turned.coeffs() - expected.coeffs()).cwiseAbs().maxCoeff(), 1e-15)
        << "angle " << angle;
    q = turned;
  }
}

TEST(TurnedBy, StaysUnitOverAMillionTurns) {
  // A marble rolling for 1000 s at 1 ms substeps: the orientation keeps unit length to rounding,
  // and turning by a vector and back returns it.
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-0.05, 0.05);
  Quat q = Quat::Identity();
  for (int n = 0; n < 1000000; ++n) q = turnedBy(q, Vec3(unit(random), unit(random), unit(random)));
  EXPECT_NEAR(q.norm(), 1.0, 1e-15);
  const Vec3 turn(0.03, -0.04, 0.02);
  const Quat back = turnedBy(turnedBy(q, turn), -turn);
  EXPECT_LT((back.coeffs() - q.coeffs()).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(turnedBy(q, Vec3::Zero()).coeffs(), q.coeffs());
}

}  // namespace
}  // namespace marble_maze
