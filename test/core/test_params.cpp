#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "marble_maze/params.h"

namespace marble_maze {
namespace {

std::string errorOf(const std::string& key, const std::string& value) {
  Params p;
  try {
    setParam(p, key, value);
  } catch (const ParamError& e) {
    return e.what();
  }
  return "";
}

TEST(Params, EveryKeyRoundTripsThroughText) {
  for (const ParamInfo& info : paramInfos()) {
    Params p;
    const std::string text = getParam(p, info.key);
    if (info.key == "start_position") continue;  // "start cell" until set
    EXPECT_NO_THROW(setParam(p, info.key, text)) << info.key << "=" << text;
    EXPECT_EQ(getParam(p, info.key), text) << info.key;
  }
}

TEST(Params, ValuesAreParsed) {
  Params p;
  setParam(p, "model", "smooth");
  setParam(p, "restitution", "0.7");
  setParam(p, "substeps", "4");
  setParam(p, "start_position", "0.01,-0.02,0.006");
  EXPECT_EQ(p.model, Model::Smooth);
  EXPECT_DOUBLE_EQ(p.restitution, 0.7);
  EXPECT_EQ(p.substeps, 4);
  EXPECT_TRUE(p.has_start_position);
  EXPECT_EQ(p.start_position, Vec3(0.01, -0.02, 0.006));
  // The list form ROS hands a node for _start_position:=[X, Y, Z], spaces and all.
  setParam(p, "start_position", " [0.02, -0.01 ,0.006] ");
  EXPECT_EQ(p.start_position, Vec3(0.02, -0.01, 0.006));
  setParam(p, "board_position", "[1,2,3]");
  EXPECT_EQ(p.board_position, Vec3(1, 2, 3));
}

TEST(Params, BadValuesNameTheKeyAndWhatWasExpected) {
  EXPECT_EQ(errorOf("restitution", "x"), "restitution: expected a number, got 'x'");
  EXPECT_EQ(errorOf("restitution", "1.5"), "restitution: 1.5 is out of range [0, 1]");
  // Just beyond a bound, the value is said exactly, not rounded onto the bound.
  EXPECT_EQ(errorOf("restitution", "1.0000001"), "restitution: 1.0000001 is out of range [0, 1]");
  EXPECT_EQ(errorOf("restitution", "nan"), "restitution: expected a finite number, got 'nan'");
  EXPECT_EQ(errorOf("model", "bouncy"),
            "model: expected one of 'smooth' or 'rolling', got 'bouncy'");
  EXPECT_EQ(errorOf("integrator", "euler"),
            "integrator: expected one of 'semi_implicit_euler', 'velocity_verlet' or 'rk4', got "
            "'euler'");
  EXPECT_EQ(errorOf("preset", "quick"),
            "preset: expected one of 'realtime', 'fast', 'accurate', 'realistic' or 'none', got "
            "'quick'");
  EXPECT_EQ(errorOf("substeps", "2.5"), "substeps: expected a whole number, got '2.5'");
  EXPECT_NE(errorOf("start_position", "1,2").find("start_position: expected three"),
            std::string::npos);
  EXPECT_NE(errorOf("restitushun", "1").find("'restitushun': unknown parameter"),
            std::string::npos);
}

TEST(ExactText, ReadsBackExactlyAndSaysNanWithoutASign) {
  for (double v : {0.1, 1.0 / 3, 1e-300, -2.5, 0.17453292519943295, 5e-324})
    EXPECT_EQ(std::strtod(exactText(v).c_str(), nullptr), v) << exactText(v);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(exactText(nan), "nan");
  EXPECT_EQ(exactText(-nan), "nan");  // a sign that printf would show as "-nan"
  EXPECT_EQ(exactText(-std::numeric_limits<double>::infinity()), "-inf");
}

TEST(ExactText, IsPrintfsShortestGeneralFormOfAtLeastSixDigits) {
  // The oracle: printf's %g at 6, 7, ... 17 digits, the first that reads back exactly.
  const auto printfs = [](double v) {
    char text[64];
    for (int digits = 6; digits <= 17; ++digits) {
      std::snprintf(text, sizeof text, "%.*g", digits, v);
      if (std::strtod(text, nullptr) == v) break;
    }
    return std::string(text);
  };
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (double v :
       {0.0, -0.0, 1.0, 1000.0, 100000.0, 1e6, 1234567.0, 0.0001, 1e-5, 1e158,
        2.2250738585072014e-308, 1.7976931348623157e308, 0.2617993877991494, 123456.5, 99999.99})
    EXPECT_EQ(exactText(v), printfs(v));
  // (A subnormal's shortest digits can be fewer than the six printf pads it to: 5e-324 rather
  // than 4.94066e-324, both read back as the same double.)
  EXPECT_EQ(exactText(5e-324), "5e-324");
  for (int n = 0; n < 300000; ++n) {
    double v;
    if (n % 3 == 0) {  // any bits that are a number
      const std::uint64_t bits = random();
      std::memcpy(&v, &bits, sizeof v);
      if (std::isnan(v)) continue;
      if (v != 0 && std::abs(v) < std::numeric_limits<double>::min()) {
        // A subnormal: printf pads its digits, std::to_chars gives the shortest in this form.
        char text[64];
        char* end = std::to_chars(text, text + sizeof text, v, std::chars_format::scientific).ptr;
        ASSERT_EQ(exactText(v), std::string(text, end)) << "bits of " << v;
        continue;
      }
    } else if (n % 3 == 1) {  // every scale a simulation meets
      v = unit(random) * std::pow(10.0, static_cast<int>(random() % 40) - 20);
    } else {  // few digits: a user's values
      v = std::round(unit(random) * 1e6) / std::pow(10.0, static_cast<int>(random() % 12));
    }
    ASSERT_EQ(exactText(v), printfs(v)) << "bits of " << v;
  }
}

TEST(Params, TheStepDividingAPeriodIsTheLongestThatDividesIt) {
  EXPECT_EQ(stepDividing(0.02, 0.001), 0.001);  // already whole: kept to the bit
  EXPECT_EQ(stepDividing(0.001, 0.001), 0.001);
  const double period = 1.0 / 55;
  EXPECT_NEAR(stepDividing(period, 0.001) * 19, period, 1e-18);  // 19 of 0.957 ms
  EXPECT_NEAR(stepDividing(period, 0.005) * 4, period, 1e-18);   // 4 of 4.545 ms
  EXPECT_EQ(stepDividing(0.001, 0.005), 0.001);                  // a period under a step
  for (double step : {1e-4, 3e-4, 0.0017, 0.004, 0.0099}) {
    const double fitted = stepDividing(period, step);
    EXPECT_LE(fitted, step);
    EXPECT_GT(fitted, step * (1 - step / period));  // one step more at most
  }
}

TEST(Params, ValidateRefusesAThresholdThatWouldMakeSemiImplicitEulerBounceAtRest) {
  Params p;
  p.integrator = IntegratorKind::SemiImplicitEuler;
  p.step = 0.01;
  p.bounce_threshold_auto = false;
  try {
    validate(p);
    FAIL() << "expected a ParamError";
  } catch (const ParamError& e) {
    EXPECT_NE(std::string(e.what()).find("bounce_threshold"), std::string::npos);
  }
  p.substeps = 10;
  EXPECT_NO_THROW(validate(p));
}

TEST(Params, TheAutomaticBounceThresholdFollowsTheStepForSemiImplicitEulerOnly) {
  Params p;
  EXPECT_EQ(getParam(p, "bounce_threshold"), "auto");
  for (double step : {1e-4, 1e-3, 5e-3, 2e-2}) {
    p.step = step;
    p.integrator = IntegratorKind::SemiImplicitEuler;
    EXPECT_DOUBLE_EQ(p.bounceThreshold(), std::max(0.02, 2 * 9.81 * step));
    EXPECT_NO_THROW(validate(p));
    p.integrator = IntegratorKind::VelocityVerlet;
    EXPECT_DOUBLE_EQ(p.bounceThreshold(), 0.02);  // its velocity does not lag: no least value
    EXPECT_NO_THROW(validate(p));
  }
  setParam(p, "bounce_threshold", "0.05");
  EXPECT_DOUBLE_EQ(p.bounceThreshold(), 0.05);
  setParam(p, "bounce_threshold", "auto");
  EXPECT_DOUBLE_EQ(p.bounceThreshold(), 0.02);
}

TEST(Params, APresetSetsTheTradeAndLaterKeysOverrideIt) {
  Params p;
  setParam(p, "preset", "fast");
  EXPECT_EQ(getParam(p, "preset"), "fast");
  const double fast_step = p.step;
  EXPECT_GT(fast_step, Params().step);  // a coarser step than the default
  setParam(p, "preset", "accurate");
  EXPECT_LT(p.step, Params().step);
  EXPECT_EQ(p.integrator, IntegratorKind::RungeKutta4);
  setParam(p, "integrator", "semi_implicit_euler");  // after the preset: it wins
  EXPECT_EQ(getParam(p, "integrator"), "semi_implicit_euler");
  EXPECT_EQ(getParam(p, "step"), "0.0001");
}

TEST(Params, TheRealisticPresetIsRealtimeWithTheRealGamesMeasuredPhysics) {
  Params realtime, p;
  setParam(realtime, "preset", "realtime");
  setParam(p, "preset", "realistic");
  EXPECT_EQ(p.integrator, realtime.integrator);
  EXPECT_EQ(p.step, realtime.step);
  EXPECT_EQ(p.model, realtime.model);
  // doc/realistic.md: a 12.7 mm, 9 g ball; rolling resistance 0.00118; wall bounce 0.11; 10 deg.
  EXPECT_EQ(p.marble_radius, 0.00635);
  EXPECT_NEAR(p.marbleMass(), 0.009, 1e-12);
  EXPECT_EQ(p.rolling_resistance, 0.00118);
  EXPECT_EQ(p.restitution, 0.11);
  EXPECT_NEAR(p.tilt_limit * 180 / 3.14159265358979323846, 10, 1e-12);
  setParam(p, "restitution", "0.3");  // after the preset: it wins
  EXPECT_EQ(p.restitution, 0.3);
}

TEST(Params, TheDefaultMarbleWeighsWhatA12MillimetreSteelBallWeighs) {
  // Against the catalogues, not the formula: a 12 mm ball of bearing steel (7.81 to 7.85 g/cm^3)
  // weighs 7.05 to 7.11 g. (Its inertia is checked by its motion: a rolling solid sphere
  // accelerates at 5/7 g sin(theta) down an incline, test_physics.cpp.)
  const Params p;
  EXPECT_GE(p.marbleMass(), 7.05e-3);
  EXPECT_LE(p.marbleMass(), 7.11e-3);
}

}  // namespace
}  // namespace marble_maze
