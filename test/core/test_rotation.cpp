#include <gtest/gtest.h>

#include <cmath>
#include <random>

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

TEST(CosSinc, OfTwoAnglesAtOnceIsEachAloneToTheBit) {
  // Roll and pitch side by side in two lanes give what each gives alone, bit for bit: angles
  // from 0 to 0.5 rad, within the series and beyond (where one lane's angle is beyond and the
  // other's within), of either sign.
  std::mt19937 random(5);
  std::uniform_real_distribution<double> angle(-0.5, 0.5);
  for (int n = 0; n < 100000; ++n) {
    const double a = n == 0 ? 0.0 : angle(random), b = n % 7 == 0 ? 0.25 : angle(random);
    CosSinc pa, pb;
    cosSinc(a * a, b * b, &pa, &pb);
    const CosSinc sa = cosSinc(a * a), sb = cosSinc(b * b);
    ASSERT_EQ(pa.cos, sa.cos) << "a " << a;
    ASSERT_EQ(pa.sinc, sa.sinc) << "a " << a;
    ASSERT_EQ(pb.cos, sb.cos) << "b " << b;
    ASSERT_EQ(pb.sinc, sb.sinc) << "b " << b;
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
