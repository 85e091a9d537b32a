// The agents' sensors, each effect measured against frames whose values say which period they
// were taken at.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "marble_maze/params.h"
#include "marble_maze/sensors.h"

namespace marble_maze {
namespace {

/// The true frame at period k: every value says k (x = k, vx = 10 k, dx = -k, ...).
Sensors::Frame truthAt(int k) {
  const double v = k;
  return {v, 2 * v, 10 * v, 20 * v, -v, -2 * v};
}

TEST(Sensors, WithoutOptionsTheAgentSeesTheTruth) {
  Sensors sensors(SensorOptions(), 55.0);
  std::uint64_t random = 1;
  EXPECT_EQ(sensors.restart(truthAt(0), &random), truthAt(0));
  for (int k = 1; k < 50; ++k) EXPECT_EQ(sensors.see(truthAt(k), &random), truthAt(k));
  EXPECT_EQ(random, 1u);  // nothing drawn
  EXPECT_EQ(sensors.measuredTilt(0.123456789), 0.123456789);
}

TEST(Sensors, ADelayShowsThePeriodThatManyBefore) {
  SensorOptions options;
  options.delay_periods = 3;
  Sensors sensors(options, 55.0);
  std::uint64_t random = 1;
  sensors.restart(truthAt(0), &random);
  for (int k = 1; k < 40; ++k)  // (before the third period, the episode's first frame)
    EXPECT_EQ(sensors.see(truthAt(k), &random), truthAt(std::max(0, k - 3))) << k;
}

TEST(Sensors, JitterAddsUpToItsPeriodsDrawnEachPeriodAndNeverGoesBack) {
  SensorOptions options;
  options.delay_periods = 1;
  options.delay_jitter = 2;
  const auto run = [&](std::uint64_t seed) {
    Sensors sensors(options, 55.0);
    std::uint64_t random = seed;
    sensors.restart(truthAt(0), &random);
    std::vector<double> seen;
    for (int k = 1; k <= 600; ++k) seen.push_back(sensors.see(truthAt(k), &random)[0]);
    return seen;
  };
  const std::vector<double> seen = run(7);
  std::set<int> lags;
  for (int k = 1; k <= 600; ++k) {
    const int lag = k - static_cast<int>(seen[k - 1]);
    if (k > 3) {
      EXPECT_TRUE(lag >= 1 && lag <= 3) << "period " << k << " lag " << lag;
    }
    if (k > 1) {
      EXPECT_GE(seen[k - 1], seen[k - 2]);  // never an older frame after a newer one
    }
    lags.insert(lag);
  }
  EXPECT_TRUE(lags.count(1) && lags.count(2) && lags.count(3));  // every delay is drawn
  EXPECT_EQ(run(7), seen);                                       // the same seed, the same
  EXPECT_NE(run(8), seen);
}

TEST(Sensors, ACameraSlowerThanTheControlHoldsItsLastFrame) {
  SensorOptions options;
  options.camera_rate = 11.0;  // a frame every fifth period at 55 Hz
  Sensors sensors(options, 55.0);
  std::uint64_t random = 1;
  sensors.restart(truthAt(0), &random);
  for (int k = 1; k <= 100; ++k)
    EXPECT_EQ(sensors.see(truthAt(k), &random), truthAt(k - k % 5)) << k;
  // A camera as fast as the control, or faster, gives every period its frame.
  options.camera_rate = 200.0;
  Sensors fast(options, 55.0);
  fast.restart(truthAt(0), &random);
  for (int k = 1; k <= 10; ++k) EXPECT_EQ(fast.see(truthAt(k), &random), truthAt(k));
}

TEST(Sensors, PositionNoiseHasItsDeviationOnThePositionAlone) {
  SensorOptions options;
  options.position_noise = 1e-3;
  Sensors sensors(options, 55.0);
  std::uint64_t random = 3;
  sensors.restart(truthAt(0), &random);
  const int n = 20000;
  double sum = 0, squares = 0;
  for (int k = 1; k <= n; ++k) {
    const Sensors::Frame& seen = sensors.see(truthAt(k), &random);
    const Sensors::Frame truth = truthAt(k);
    const double noise = seen[0] - truth[0];
    sum += noise;
    squares += noise * noise;
    EXPECT_EQ(seen[2], truth[2]);  // the velocities are the camera's estimate, not noisy here
    EXPECT_EQ(seen[3], truth[3]);
    // The waypoint stays put: the offset to it moves against the noise.
    EXPECT_NEAR(seen[0] + seen[4], truth[0] + truth[4], 1e-12);
    EXPECT_NEAR(seen[1] + seen[5], truth[1] + truth[5], 1e-12);
  }
  const double mean = sum / n, deviation = std::sqrt(squares / n - mean * mean);
  EXPECT_LT(std::abs(mean), 4 * 1e-3 / std::sqrt(n));  // four standard errors
  EXPECT_NEAR(deviation, 1e-3, 0.03e-3);               // 3%: about six standard errors
}

TEST(Sensors, TheTiltIsReportedInWholeQuanta) {
  SensorOptions options;
  options.tilt_quantum = M_PI / 180;  // Moab's whole degrees
  Sensors sensors(options, 55.0);
  for (double degrees : {-10.4, -0.6, -0.4, 0.0, 0.3, 0.5000001, 7.49, 7.51}) {
    const double tilt = degrees * M_PI / 180;
    const double measured = sensors.measuredTilt(tilt);
    EXPECT_NEAR(measured, std::round(degrees) * M_PI / 180, 1e-15) << degrees;
    EXPECT_LE(std::abs(measured - tilt), 0.5 * M_PI / 180 + 1e-15) << degrees;
  }
}

TEST(Sensors, AnOptionOutOfRangeIsRefusedNamingIt) {
  const auto why = [](SensorOptions options) {
    try {
      Sensors sensors(options, 55.0);
    } catch (const ParamError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  SensorOptions o;
  o.delay_periods = -1;
  EXPECT_EQ(why(o), "delay_periods: -1 is out of range [0, 1000]");
  o = SensorOptions();
  o.position_noise = std::nan("");
  EXPECT_EQ(why(o), "position_noise: nan is out of range [0, 1] m");
  o = SensorOptions();
  o.camera_rate = -5;
  EXPECT_EQ(why(o), "camera_rate: -5 is out of range [0, inf) Hz");
  o = SensorOptions();
  o.tilt_quantum = 1;
  EXPECT_EQ(why(o), "tilt_quantum: 1 is out of range [0, 0.5] rad");
}

}  // namespace
}  // namespace marble_maze
