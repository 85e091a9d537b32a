// The integrators against closed forms. Velocity Verlet and RK4 follow the exact parabola under a
// constant acceleration and meet tiles on it, so free flight, inclines and bounces carry only
// rounding error at any step: the tolerances here are 1e-9 relative. Semi-implicit Euler is
// first order: its errors are checked against what the scheme itself predicts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <utility>
#include <vector>

#include "marble_maze/simulation.h"
#include "scenes.h"

namespace marble_maze {
namespace {

using test::kPi;
using test::placed;

constexpr double kRadius = 0.006;
constexpr double kExact = 1e-9;  // relative: rounding only
const IntegratorKind kExactSchemes[] = {IntegratorKind::VelocityVerlet,
                                        IntegratorKind::RungeKutta4};

using test::name;
using test::scheme;

void run(Simulation* sim, double seconds) {
  const auto steps = std::lround(seconds / sim->params().step);
  for (long i = 0; i < steps; ++i) sim->step();
}

// --- Inclines --------------------------------------------------------------------------------

/// Distance down an incline of angle theta after one second from rest.
double inclineDistance(Params p, double theta) {
  p = placed(p, {-0.95, 0, kRadius});
  p.initial_pitch = theta;  // positive pitch lowers the board's +x end
  p.tilt_limit = 1.5;
  Simulation sim(test::flatFloor(200, 10, 0.01, p));
  const Vec3 start = sim.marble().position;
  run(&sim, 1.0);
  EXPECT_EQ(sim.marble().phase, MarblePhase::Free);
  return (sim.marble().position - start).norm();
}

TEST(ExactSchemes, InclinesFromRestAreExactAtAnyAngleAndStep) {
  for (IntegratorKind integrator : kExactSchemes)
    for (Model model : {Model::Rolling, Model::Smooth})
      for (double step : {1e-4, 1e-3, 4e-3, 1e-2})
        for (double degrees : {2.0, 10.0, 20.0}) {
          const Params p = scheme(integrator, model, step);
          const double theta = degrees * kPi / 180, t = 1.0;
          // Rolling without slipping: a = (5/7) g sin(theta); sliding: a = g sin(theta).
          const double a = (model == Model::Rolling ? 5.0 / 7.0 : 1.0) * 9.81 * std::sin(theta);
          const double expected = 0.5 * a * t * t;
          // 20 degrees needs friction 0.3 > (2/7) tan(20 deg) = 0.10 to roll: it does.
          EXPECT_NEAR(inclineDistance(p, theta), expected, kExact * expected)
              << name(p) << " at " << degrees << " degrees";
        }
}

TEST(SemiImplicitEuler, InclineErrorIsItsFirstOrderStepOverTime) {
  // x_n = a h^2 n (n + 1) / 2 = a t (t + h) / 2: too far by exactly h / t.
  for (double step : {1e-3, 1e-2}) {
    const Params p = scheme(IntegratorKind::SemiImplicitEuler, Model::Rolling, step);
    const double a = 5.0 / 7.0 * 9.81 * std::sin(0.1);
    const double exact = 0.5 * a;
    EXPECT_NEAR(inclineDistance(p, 0.1) / exact - 1, step / 1.0, 1e-9) << name(p);
  }
}

// --- Bounces ---------------------------------------------------------------------------------

/// The apex heights above the floor after each of the first `count` bounces of a marble
/// dropped from h0, each taken from the state just after the bounce as z + v_z^2 / (2 g).
std::vector<double> apexesAfterBounces(const Params& params, double h0, int count) {
  const Params p = placed(params, {0, 0, kRadius + h0});
  Simulation sim(test::flatFloor(10, 10, 0.01, p));
  std::vector<double> apexes;
  while (static_cast<int>(apexes.size()) < count && sim.time() < 60) {
    sim.step();
    if (sim.events().empty()) continue;
    const Marble& m = sim.marble();
    EXPECT_EQ(sim.events().size(), 1u) << "one bounce per step at these heights";
    apexes.push_back(m.position.z() - kRadius + m.velocity.z() * m.velocity.z() / (2 * 9.81));
  }
  return apexes;
}

TEST(ExactSchemes, BounceApexesFollowRestitutionSquaredToRounding) {
  const double h0 = 0.05, e = 0.7;
  for (IntegratorKind integrator : kExactSchemes)
    for (Model model : {Model::Smooth, Model::Rolling})
      for (double step : {1e-3, 1e-2}) {
        const Params p = scheme(integrator, model, step, e);
        const auto apexes = apexesAfterBounces(p, h0, 5);
        ASSERT_EQ(apexes.size(), 5u) << name(p);
        for (int k = 1; k <= 5; ++k) {
          const double expected = h0 * std::pow(e, 2 * k);
          EXPECT_NEAR(apexes[k - 1], expected, kExact * expected) << name(p) << " apex " << k;
        }
      }
}

TEST(ExactSchemes, AnElasticMarbleKeepsItsHeightForAHundredBounces) {
  const double h0 = 0.02;
  for (IntegratorKind integrator : kExactSchemes) {
    const Params p = scheme(integrator, Model::Smooth, 1e-3, 1.0);
    const auto apexes = apexesAfterBounces(p, h0, 100);
    ASSERT_EQ(apexes.size(), 100u) << name(p);
    EXPECT_NEAR(apexes.back(), h0, kExact * h0) << name(p);
  }
}

TEST(SemiImplicitEuler, AnElasticMarbleNeverGainsHeight) {
  // Its velocity lags half a step: the height the energy allows is taken at that instant.
  const double h0 = 0.02;
  const Params p = placed(scheme(IntegratorKind::SemiImplicitEuler, Model::Smooth, 1e-3, 1.0),
                          {0, 0, kRadius + h0});
  Simulation sim(test::flatFloor(10, 10, 0.01, p));
  const double weight = p.marbleMass() * 9.81;
  double highest = 0;
  int bounces = 0;
  while (bounces < 100 && sim.time() < 60) {
    sim.step();
    bounces += static_cast<int>(sim.events().size());
    highest = std::max(highest, sim.energy() / weight - kRadius);
  }
  ASSERT_EQ(bounces, 100);
  EXPECT_LE(highest, h0 * (1 + 1e-12));
  EXPECT_NEAR(sim.energy() / weight - kRadius, h0, 0.01 * h0);  // 1%: it loses a little
}

TEST(ExactSchemes, ABounceSequenceEndsAtRestWithTheSameBouncesAtAnyStep) {
  // e = 0.9 from 24 mm: an impact is a bounce while it is faster than 0.02 m/s, 34 of them. A
  // bounce shorter than a step is found on the parabola too, and the marble comes to rest on the
  // floor, not hovering above it.
  for (IntegratorKind integrator : kExactSchemes)
    for (double step : {1e-3, 5e-3, 1e-2, 2e-2}) {
      const Params p = placed(scheme(integrator, Model::Rolling, step, 0.9), {0, 0, 0.03});
      Simulation sim(test::flatFloor(10, 10, 0.01, p));
      int bounces = 0;
      while (sim.time() < 3) {
        sim.step();
        bounces += static_cast<int>(sim.events().size());
      }
      EXPECT_EQ(bounces, 34) << name(p);
      EXPECT_NEAR(sim.marble().position.z(), kRadius, 1e-9) << name(p);
      EXPECT_LT(sim.marble().velocity.norm(), 1e-12) << name(p);
    }
}

TEST(AllSchemes, AnImpactAtTheVeryEndOfAStepLeavesNothingToMove) {
  // Placed so that the fall meets the floor exactly at the end of the first 10 ms step, where
  // what is left of the step is zero long.
  for (IntegratorKind integrator : {IntegratorKind::SemiImplicitEuler,
                                    IntegratorKind::VelocityVerlet, IntegratorKind::RungeKutta4}) {
    const double h = 0.01, lag = integrator == IntegratorKind::SemiImplicitEuler ? 1.0 : 0.5;
    Params p = placed(scheme(integrator, Model::Smooth, h), {0, 0, kRadius + lag * 9.81 * h * h});
    Simulation sim(test::flatFloor(10, 10, 0.01, p));
    for (int i = 0; i < 10; ++i) sim.step();
    EXPECT_TRUE(sim.marble().position.allFinite()) << name(p);
    EXPECT_EQ(sim.marble().phase, MarblePhase::Free) << name(p);
    EXPECT_NEAR(sim.marble().position.z(), kRadius, 1e-6) << name(p);
  }
}

// --- Slip to roll, walls, board kicks --------------------------------------------------------

TEST(ExactSchemes, ASlidingMarbleRollsAtFiveSeventhsOfItsLaunchSpeed) {
  // Friction conserves the angular momentum about the contact point: m v0 r = (m + I / r^2) v r.
  for (IntegratorKind integrator : kExactSchemes)
    for (double step : {1e-3, 1e-2}) {
      const Params p =
          placed(scheme(integrator, Model::Rolling, step), {-0.9, 0, kRadius}, {0.7, 0, 0});
      Simulation sim(test::flatFloor(200, 10, 0.01, p));
      run(&sim, 1.0);  // slips for 2 v0 / (7 mu g) = 0.07 s, then rolls
      EXPECT_NEAR(sim.marble().velocity.x(), 0.5, kExact * 0.5) << name(p);
    }
}

/// A marble rolling (or sliding) at 0.5 m/s into a wall, without gravity so that the floor
/// touches it but does not press: the wall alone acts. Its x velocity before and after.
std::pair<double, double> wallImpact(const Params& params) {
  const AxisSlots x(0.005, 0.0221, 5), y(0.005, 0.0221, 5), z(0.005, 0.012, 2);
  Maze maze = test::floorMaze(x, y, z);
  for (int j = 0; j < 5; ++j) maze.setSolid({4, j, 1}, true);
  Params p = placed(params, {-0.01, 0, kRadius});
  p.gravity = 0;
  Simulation sim({maze, p});
  const Vec3 spin = p.model == Model::Rolling ? Vec3(0, 0.5 / kRadius, 0) : Vec3::Zero();
  sim.placeMarble(p.start_position, {0.5, 0, 0}, spin);
  while (sim.events().empty() && sim.time() < 1) sim.step();
  EXPECT_EQ(sim.events().size(), 1u);
  return {sim.events().empty() ? 0 : sim.events()[0].speed, sim.marble().velocity.x()};
}

TEST(ExactSchemes, AHeadOnWallImpactLeavesAtETimesTheApproach) {
  for (IntegratorKind integrator : kExactSchemes)
    for (Model model : {Model::Smooth, Model::Rolling})
      for (double step : {1e-3, 1e-2}) {
        const Params p = scheme(integrator, model, step, 0.7);
        const auto [approach, after] = wallImpact(p);
        EXPECT_NEAR(approach, 0.5, kExact * 0.5) << name(p);
        EXPECT_NEAR(after, -0.7 * 0.5, kExact * 0.35) << name(p);
      }
}

TEST(ExactSchemes, AFlightAfterABoardKickLandsWhenTheParabolaMeetsTheBoard) {
  // A marble at rest on a level board 0.1 m from the pivot; the board pitches at -2 rad/s for
  // one step and stops. Eq. (1) with the surface velocity (0, 0, 0.2) m/s at the contact gives
  // v' = (1 + e) 0.2 = 0.34 m/s up at t = 0, and the marble flies on the parabola p0 + v' t -
  // g t^2 / 2 until it touches the board's plane, now pitched by -2 h: n . p(T) = r.
  for (IntegratorKind integrator : kExactSchemes)
    for (double step : {1e-3, 1e-2}) {
      Params p = placed(scheme(integrator, Model::Smooth, step, 0.7), {0.1, 0, kRadius});
      p.tilt_rate_limit = 0;
      Simulation sim(test::flatFloor(40, 10, 0.01, p));
      sim.setTiltRate(0, -2.0);
      sim.step();
      ASSERT_EQ(sim.events().size(), 1u) << name(p);
      sim.setTiltRate(0, 0);
      const double pitch = sim.board().pitch(), g = 9.81, v = 0.34;
      const Vec3 n(std::sin(pitch), 0, std::cos(pitch)), p0(0.1, 0, kRadius);
      // n.p0 + n_z v T - n_z g T^2 / 2 = r: the larger root.
      const double a = -0.5 * g * n.z(), b = v * n.z(), c = n.dot(p0) - kRadius;
      const double landing = (-b - std::sqrt(b * b - 4 * a * c)) / (2 * a);
      double hit = -1;
      while (hit < 0 && sim.time() < 1) {
        sim.step();
        if (!sim.events().empty()) hit = sim.events()[0].time;
      }
      EXPECT_NEAR(hit, landing, kExact * step) << name(p);
    }
}

// --- A turning board -------------------------------------------------------------------------

/// The error of a marble's position along a board pitching from level at a constant rate w,
/// after 1 s of steps of `step`, against the closed form. It starts 0.3 m from the pivot at rest
/// on the board (moving with it: velocity w x p, and spin w when it rolls). In the board's frame,
/// along it: gravity g sin(w t) and the centrifugal force w^2 x; the Coriolis force and the
/// centrifugal force on the centre's height above the axis act along the normal, which the board
/// takes. So x'' = c (w^2 x + g sin(w t)), c = 1 for a frictionless marble and 5/7 for a rolling
/// one (its spin takes 2/5 m r^2 / (m r^2 + 2/5 m r^2) of the force). With k = w sqrt(c):
/// x(t) = x0 cosh(k t) + B sinh(k t) + D sin(w t), D = -c g / (w^2 + k^2), B = -D w / k.
double turningBoardError(IntegratorKind integrator, Model model, double step) {
  const double w = 0.5, x0 = 0.3, duration = 1.0, r = kRadius;
  Params p = placed(scheme(integrator, model, step), {x0, 0, r}, Vec3(w * r, 0, -w * x0));
  p.tilt_rate_limit = 0;
  p.tilt_limit = 1.0;
  p.rolling_resistance = 0;
  Simulation sim(test::flatFloor(500, 10, 0.01, p));
  if (model == Model::Rolling) sim.placeMarble(p.start_position, p.start_velocity, {0, w, 0});
  sim.setTiltRate(0, w);
  for (int i = 0; i < std::lround(duration / step); ++i) {
    sim.step();
    EXPECT_TRUE(sim.events().empty()) << name(p);  // it rides on the board, never leaving it
  }
  const double t = sim.time(), g = p.gravity;
  const double c = model == Model::Rolling ? 5.0 / 7.0 : 1.0, k = w * std::sqrt(c);
  const double d = -c * g / (w * w + k * k), b = -d * w / k;
  const Vec3 on_board = sim.marbleInBoard();
  EXPECT_NEAR(on_board.z(), r, 1e-12) << name(p);
  return on_board.x() - (x0 * std::cosh(k * t) + b * std::sinh(k * t) + d * std::sin(w * t));
}

TEST(TurningBoard, EachSchemeConvergesAtItsOrderOnABoardPitchingAtAConstantRate) {
  // From 10 ms to 0.1 ms, each scheme's error falls as the step to its order (within 0.15; semi-
  // implicit Euler's within 0.3 at coarse steps), sliding and rolling, until it is rounding
  // (RK4 from 1 ms). Velocity Verlet's contacts push along the normal of the substep's middle and
  // hold the velocity to the surfaces of its end (as RATTLE does); RK4 takes the stretch in the
  // board's frame. With the surfaces of the start both were first order, 82 um off at 1 ms.
  constexpr double kRounding = 1e-12;  // m: 10,000 steps of a position of about 1 m
  const std::pair<IntegratorKind, double> orders[] = {{IntegratorKind::SemiImplicitEuler, 1},
                                                      {IntegratorKind::VelocityVerlet, 2},
                                                      {IntegratorKind::RungeKutta4, 4}};
  const double steps[] = {1e-2, 4e-3, 2e-3, 1e-3, 5e-4, 1e-4};
  for (const auto& [integrator, order] : orders)
    for (Model model : {Model::Smooth, Model::Rolling}) {
      const Params p = scheme(integrator, model, 1e-3);
      double coarser = 0;
      for (std::size_t i = 0; i < std::size(steps); ++i) {
        const double error = std::abs(turningBoardError(integrator, model, steps[i]));
        if (order == 4 && steps[i] <= 1e-3) {
          EXPECT_LT(error, kRounding) << name(p) << ", " << steps[i] << " s";
          continue;
        }
        if (i > 0) {
          const double measured = std::log(coarser / error) / std::log(steps[i - 1] / steps[i]);
          const double within = order == 1 && steps[i] > 1e-3 ? 0.3 : 0.15;
          EXPECT_NEAR(measured, order, within) << name(p) << ", from " << steps[i - 1] << " s";
        }
        coarser = error;
      }
    }
  // Velocity Verlet at 1 ms within 2 um of the closed form, its error a quarter of 2 ms's or
  // less (3.5 times smaller at least).
  for (Model model : {Model::Smooth, Model::Rolling}) {
    const double fine = std::abs(turningBoardError(IntegratorKind::VelocityVerlet, model, 1e-3));
    const double coarse = std::abs(turningBoardError(IntegratorKind::VelocityVerlet, model, 2e-3));
    EXPECT_LT(fine, 2e-6) << static_cast<int>(model);
    EXPECT_GT(coarse / fine, 3.5) << static_cast<int>(model);
  }
}

TEST(TurningBoard, RK4AndVelocityVerletPlayTheSameGame) {
  // The closed classic maze under a board circling at 0.1 rad, a servo following commands at
  // 50 Hz, for 2 s at 0.1 ms x 4: the marble rolls, meets walls and rolls along them. RK4 takes
  // what it rolls on one face in the board's frame and the rest as velocity Verlet does, and the
  // two play the same game to 2 um. (Taken in the board's frame against a wall and the floor at
  // once too, RK4's stages disagreed as a stick turned to slip between them: 35 um apart.)
  const auto play = [](IntegratorKind integrator) {
    Params p = scheme(integrator, Model::Rolling, 1e-4, 0.5);
    p.substeps = 4;
    Simulation sim(Scene{test::closedClassic(), p});
    for (long i = 0; i < 20000; ++i) {
      const double t = 0.02 * std::floor(sim.time() / 0.02 + 1e-9), angle = kPi * t;
      sim.setTargetTilt(t == 0 ? 0 : 0.1 * std::sin(angle), t == 0 ? 0 : 0.1 * std::cos(angle));
      sim.step();
    }
    return sim.marbleInBoard();
  };
  EXPECT_LT((play(IntegratorKind::RungeKutta4) - play(IntegratorKind::VelocityVerlet)).norm(),
            2e-6);
}

// --- Drag: where RK4 beats velocity Verlet ---------------------------------------------------

/// The error in speed after 1 s of gravity-free flight under quadratic drag, against
/// v(t) = v0 / (1 + k v0 t).
double dragError(IntegratorKind integrator, double step) {
  const Params p = test::dragFlight(scheme(integrator, Model::Smooth, step));
  Simulation sim(test::flatFloor(10, 10, 0.01, p));
  run(&sim, 1.0);
  return std::abs(sim.marble().velocity.x() - test::dragFlightSpeed(p, 1.0));
}

TEST(Drag, EachSchemeConvergesAtItsOrder) {
  // Halving the step divides the error by 2^order (within 20%, for what is not yet asymptotic).
  const std::pair<IntegratorKind, int> orders[] = {{IntegratorKind::SemiImplicitEuler, 1},
                                                   {IntegratorKind::VelocityVerlet, 2},
                                                   {IntegratorKind::RungeKutta4, 4}};
  for (const auto& [integrator, order] : orders) {
    const double coarse = dragError(integrator, 0.02), fine = dragError(integrator, 0.01);
    EXPECT_NEAR(std::log2(coarse / fine), order, 0.2) << static_cast<int>(integrator);
  }
  EXPECT_LT(dragError(IntegratorKind::RungeKutta4, 0.01),
            1e-3 * dragError(IntegratorKind::VelocityVerlet, 0.01));
}

TEST(Drag, RK4TakesTheContactsIntoEachStageSoARollingMarbleIsFourthOrderToo) {
  // Rolling on a level floor, the spin takes its share of the drag: v = v0 / (1 + (5/7) k v0 t).
  // Each RK4 stage asks the contacts what they do, so the error is at rounding at a 10 ms step;
  // velocity Verlet's trapezoid leaves a second-order error.
  const auto error = [](IntegratorKind integrator) {
    Params p = placed(scheme(integrator, Model::Rolling, 0.01), {-24, 0, kRadius});
    p.drag_coefficient = 0.47;
    Simulation sim({test::floorMaze(AxisSlots::uniform(1.0, 50), AxisSlots::uniform(1.0, 3),
                                    AxisSlots::uniform(0.005, 2)),
                    p});
    sim.placeMarble(p.start_position, {20, 0, 0}, {0, 20 / kRadius, 0});
    run(&sim, 1.0);
    const double k =
        p.air_density * p.drag_coefficient * kPi * kRadius * kRadius / (2 * p.marbleMass());
    const double expected = 20 / (1 + 5.0 / 7.0 * k * 20);
    return std::abs(sim.marble().velocity.x() - expected) / expected;
  };
  EXPECT_LT(error(IntegratorKind::RungeKutta4), 1e-12);
  EXPECT_GT(error(IntegratorKind::VelocityVerlet), 1e-9);  // the test can tell them apart
  EXPECT_LT(error(IntegratorKind::VelocityVerlet), 1e-7);
}

}  // namespace
}  // namespace marble_maze
