// The engine against closed-form physics and conservation laws. Each tolerance is stated where
// it is used.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "marble_maze/contact_solver.h"
#include "marble_maze/simulation.h"
#include "scenes.h"

namespace marble_maze {
namespace {

using test::kPi;
using test::placed;

constexpr double kRadius = 0.006;

double run(Simulation* sim, double seconds) {
  const auto steps = static_cast<int>(std::lround(seconds / sim->params().step));
  for (int i = 0; i < steps; ++i) sim->step();
  return sim->time();
}

Params model(Model m, double restitution = 0.5) {
  Params p;
  p.model = m;
  p.restitution = restitution;
  return p;
}

// --- Incline -------------------------------------------------------------------------------

double inclineDistance(Model m, double theta, double seconds) {
  Params p = placed(model(m), {-0.95, 0, kRadius});
  p.initial_pitch = theta;  // positive pitch lowers the board's +x end
  Simulation sim(test::flatFloor(200, 10, 0.01, p));
  const Vec3 start = sim.marble().position;
  run(&sim, seconds);
  EXPECT_EQ(sim.marble().phase, MarblePhase::Free);
  return (sim.marble().position - start).norm();
}

TEST(Incline, RollingSphereCoversFiveFourteenthsGSinThetaTSquared) {
  const double theta = 10 * kPi / 180, g = 9.81;
  const double expected = 5.0 / 14.0 * g * std::sin(theta) * 1.0;
  EXPECT_NEAR(inclineDistance(Model::Rolling, theta, 1.0), expected, 0.005 * expected);  // 0.5%
}

TEST(Incline, SmoothSphereCoversHalfGSinThetaTSquared) {
  const double theta = 10 * kPi / 180, g = 9.81;
  const double expected = 0.5 * g * std::sin(theta) * 1.0;
  EXPECT_NEAR(inclineDistance(Model::Smooth, theta, 1.0), expected, 0.005 * expected);  // 0.5%
}

TEST(Incline, RollingSphereRollsWithoutSlipping) {
  Params p = placed(model(Model::Rolling), {-0.95, 0, kRadius});
  p.initial_pitch = 10 * kPi / 180;
  Simulation sim(test::flatFloor(200, 10, 0.01, p));
  run(&sim, 0.5);
  const Marble& m = sim.marble();
  const Vec3 n = sim.gridFrame().rotation.col(2);
  const Vec3 contact_point_velocity = m.velocity + m.angular_velocity.cross(-kRadius * n);
  EXPECT_LT(contact_point_velocity.norm(), 1e-9);  // m/s
}

// --- Bounce ----------------------------------------------------------------------------------

std::vector<double> apexHeights(Model m, double step, int count) {
  const double h0 = 0.05, e = 0.7;
  Params p = placed(model(m, e), {0, 0, kRadius + h0});
  p.step = step;
  Simulation sim(test::flatFloor(10, 10, 0.01, p));
  std::vector<double> apexes;
  double previous = sim.marble().position.z(), rising = false;
  while (static_cast<int>(apexes.size()) < count && sim.time() < 3) {
    sim.step();
    const double z = sim.marble().position.z();
    if (rising && z < previous) apexes.push_back(previous - kRadius);
    rising = z > previous;
    previous = z;
  }
  return apexes;
}

TEST(Bounce, ApexHeightsFollowRestitutionSquared) {
  const double h0 = 0.05, e = 0.7;
  for (Model m : {Model::Smooth, Model::Rolling}) {
    const auto apexes = apexHeights(m, Params().step, 5);
    ASSERT_EQ(apexes.size(), 5u);
    for (int k = 1; k <= 5; ++k) {
      const double expected = h0 * std::pow(e, 2 * k);
      EXPECT_NEAR(apexes[k - 1], expected, 0.01 * expected) << "apex " << k;  // 1%
    }
  }
}

// --- Rest ------------------------------------------------------------------------------------

TEST(Rest, AMarbleAtRestStaysAtRestFor100Seconds) {
  for (Model m : {Model::Smooth, Model::Rolling}) {
    Simulation sim(test::flatFloor(10, 10, 0.01, placed(model(m), {0.001, -0.002, kRadius})));
    const Vec3 start = sim.marble().position;
    const double energy0 = sim.energy();
    double max_vz = 0, max_rise = 0;
    while (sim.time() < 100) {
      sim.step();
      max_vz = std::max(max_vz, std::abs(sim.marble().velocity.z()));
      max_rise = std::max(max_rise, sim.energy() - energy0);
    }
    EXPECT_LT((sim.marble().position - start).norm(), 1e-6);  // m
    EXPECT_LT(max_vz, 1e-6);                                  // m/s
    EXPECT_LE(max_rise, 1e-15);  // J: the energy never rises (rounding aside)
    EXPECT_TRUE(sim.events().empty());
  }
}

TEST(Rest, AMarbleAtRestSleepsAndWakesToTheBitsItWouldHaveHadAwake) {
  // Two runs of the same inputs: `a` sleeps; `b` is restored from its own state before every
  // step, which wakes it, so that it steps in full throughout.
  for (Model m : {Model::Smooth, Model::Rolling}) {
    const Scene scene = test::flatFloor(10, 10, 0.01, placed(model(m), {0.001, -0.002, kRadius}));
    Simulation a(scene), b(scene);
    int first_rest = -1, rests = 0;
    for (int i = 0; i < 6000; ++i) {
      // At rest for 1 s, a tilt from 1 s to 1.5 s, level again after.
      const double roll = i >= 1000 && i < 1500 ? 0.05 : 0.0;
      a.setTargetTilt(roll, 0);
      b.setTargetTilt(roll, 0);
      b.restore(b.state());
      const std::uint64_t substeps = a.counts().substeps;
      const bool asleep = a.resting();
      a.step();
      b.step();
      if (asleep) {
        EXPECT_EQ(a.counts().substeps, substeps) << i;  // asleep, a step costs nothing
      }
      if (a.resting()) {
        if (first_rest < 0) first_rest = i;
        ++rests;
      }
      ASSERT_TRUE(sameBits(a.marble().position, b.marble().position))
          << test::name(a.params()) << i;
      ASSERT_TRUE(sameBits(a.marble().velocity, b.marble().velocity)) << i;
      ASSERT_TRUE(sameBits(a.marble().angular_velocity, b.marble().angular_velocity)) << i;
      ASSERT_TRUE(sameBits(a.marble().orientation, b.marble().orientation)) << i;
      ASSERT_TRUE(sameBits(a.board().roll(), b.board().roll())) << i;
    }
    // It falls asleep within 10 steps of being put down, and wakes for the tilt.
    EXPECT_GE(first_rest, 0);
    EXPECT_LT(first_rest, 10);
    EXPECT_LT(rests, 6000 - 500);
  }
}

// --- Seams -----------------------------------------------------------------------------------

TEST(Seams, RollingOverAHundredFloorTilesStaysOnTheSurface) {
  // Alternating 5 mm and 22.1 mm tiles: 101 tiles along x, seams at every boundary; the
  // diagonal run crosses seams along y as well.
  const AxisSlots x(0.005, 0.0221, 101), y(0.005, 0.0221, 41), z = AxisSlots::uniform(0.005, 1);
  for (Model m : {Model::Smooth, Model::Rolling}) {
    for (const Vec3& v : {Vec3(0.5, 0, 0), Vec3(0.5 * std::cos(0.3), 0.5 * std::sin(0.3), 0)}) {
      const double x0 = -x.length() / 2 + 0.01;
      Params p = placed(model(m), {x0, -0.22, kRadius}, v);
      Simulation sim({test::floorMaze(x, y, z), p});
      double max_across = 0;
      int tiles_crossed = 0;
      int last_slot = sim.maze().cellAt(sim.gridFrame().toGrid(sim.marble().position)).i;
      while (sim.marbleInBoard().x() < x.length() / 2 - 0.02 && sim.time() < 5) {
        sim.step();
        max_across = std::max(max_across, std::abs(sim.marble().velocity.z()));
        const int slot = sim.maze().cellAt(sim.gridFrame().toGrid(sim.marble().position)).i;
        tiles_crossed += slot != last_slot;
        last_slot = slot;
      }
      EXPECT_GE(tiles_crossed, 95);
      EXPECT_LT(max_across, 1e-6);  // m/s across the floor
      EXPECT_TRUE(sim.events().empty());
    }
  }
}

TEST(Seams, SlidingAlongAWallOfAHundredTilesStaysOnTheWall) {
  // A wall along x (y slot 2, layer 1) of 101 alternating tiles; the board rolled slightly so
  // that the marble leans on the wall while it slides along it.
  const AxisSlots x(0.005, 0.0221, 101), y(0.005, 0.0221, 5), z(0.005, 0.012, 2);
  Maze maze = test::floorMaze(x, y, z);
  for (int i = 0; i < x.count(); ++i) maze.setSolid({i, 2, 1}, true);
  const double wall_side = y.lower(2) - maze.pivot().y();  // board y of the wall's -y face
  for (Model m : {Model::Smooth, Model::Rolling}) {
    Params p =
        placed(model(m), {-x.length() / 2 + 0.01, wall_side - kRadius, kRadius}, {0.5, 0, 0});
    p.initial_roll = -0.02;  // lowers the +y side: gravity leans the marble on the wall
    Simulation sim({maze, p});
    double max_across = 0;
    while (sim.marbleInBoard().x() < x.length() / 2 - 0.02 && sim.time() < 5) {
      sim.step();
      const Vec3 v_board = sim.gridFrame().rotation.transpose() * sim.marble().velocity;
      max_across = std::max({max_across, std::abs(v_board.y()), std::abs(v_board.z())});
    }
    EXPECT_GT(sim.marbleInBoard().x(), x.length() / 2 - 0.02);
    EXPECT_LT(max_across, 1e-6);  // m/s across the wall and the floor
  }
}

// --- Impacts ---------------------------------------------------------------------------------

struct Impact {
  Vec3 before, after;
};

/// A marble sent at a wall (the +x side, x slot 3 of a small maze), its velocity in the board
/// frame just before and just after the first collision.
Impact hitWall(Model m, const Vec3& velocity, const Vec3& spin = Vec3::Zero()) {
  const AxisSlots x(0.005, 0.0221, 5), y(0.005, 0.0221, 5), z(0.005, 0.012, 2);
  Maze maze = test::floorMaze(x, y, z);
  for (int j = 0; j < 5; ++j) maze.setSolid({4, j, 1}, true);
  Params p = placed(model(m, 0.7), {-0.01, 0, kRadius}, velocity);
  p.gravity = 0;  // the floor touches but does not press: the impact alone
  Simulation sim({maze, p});
  Impact result{velocity, velocity};
  sim.placeMarble(p.start_position, velocity, spin);
  for (int i = 0; i < 1000; ++i) {
    result.before = sim.marble().velocity;
    sim.step();
    if (!sim.events().empty()) break;
  }
  EXPECT_FALSE(sim.events().empty());
  sim.step();
  result.after = sim.marble().velocity;
  return result;
}

TEST(Impact, HeadOnTheNormalSpeedLeavesAtETimesItsApproach) {
  for (Model m : {Model::Smooth, Model::Rolling}) {
    const Vec3 spin = m == Model::Rolling ? Vec3(0, 0.5 / kRadius, 0) : Vec3::Zero();
    const Impact i = hitWall(m, {0.5, 0, 0}, spin);
    EXPECT_NEAR(i.after.x(), -0.7 * i.before.x(), 0.01 * 0.7 * i.before.x());  // 1%
  }
}

TEST(Impact, SmoothModelKeepsTheTangentialSpeed) {
  const Impact i = hitWall(Model::Smooth, {0.5, 0.2, 0});
  EXPECT_NEAR(i.after.x(), -0.7 * 0.5, 0.01 * 0.35);
  EXPECT_NEAR(i.after.y(), 0.2, 1e-12);
}

TEST(Impact, ATiltingBoardKicksARestingMarbleAsEquationOneSays) {
  // A marble at rest on a level board, 0.1 m from the pivot along x. The board starts to pitch
  // at -2 rad/s, lifting that point at w x (p - pivot) = (0, -2, 0) x (0.1, 0, 0) = (0, 0, 0.2)
  // m/s. Eq. (1) with v_m = 0, n = +z, e = 0.7: v' = -(1 + e)((0 - 0.2)) n = 0.34 m/s up.
  Params p = placed(model(Model::Smooth, 0.7), {0.1, 0, kRadius});
  p.tilt_rate_limit = 0;  // unlimited: the board starts at full rate
  Simulation sim(test::flatFloor(40, 10, 0.01, p));
  sim.setTiltRate(0, -2.0);
  sim.step();
  ASSERT_EQ(sim.events().size(), 1u);
  EXPECT_NEAR(sim.events()[0].speed, 0.2, 0.002);  // 1%
  // After the kick the step's gravity acts on the flight: 0.34 m/s less g h along n.
  const Vec3 n = sim.gridFrame().rotation.col(2);
  const double expected = 0.34 - p.gravity * p.step * n.z();
  EXPECT_NEAR(sim.marble().velocity.dot(n), expected, 0.01 * expected);  // 1%
}

TEST(Impact, AKickShorterThanAStepLandsInsideTheStepAndEveryBounceAfterItComes) {
  // A marble at rest 0.07 m from the pivot on a level floor (e = 0.55); at 30 ms the board
  // starts to roll at its rate limit, 1.3 rad/s (no servo lag), and kicks it up at
  // 1.3 x 0.07 = 0.091 m/s: it leaves the floor at e x 0.091 = 0.050 m/s relative to it and lands
  // on the turning floor 10.19 ms later, then bounces at 0.050 and 0.0275 m/s. The landing is
  // where the parabola p(s) = (0, 0.07, r + 0.091 (1 + e) s - g s^2 / 2) meets the plane turned
  // by 1.3 s: -0.07 sin(1.3 s) + z(s) cos(1.3 s) = r (bisection, below). At steps of 10 and 20 ms
  // the flight is shorter than a step, and each bounce comes.
  const double w = 1.3, e = 0.55, y = 0.07;
  const auto kick = [&](double step) {
    Params p = placed(model(Model::Rolling, e), {0, y, kRadius});
    p.step = step;
    p.tilt_rate_limit = w;
    p.tilt_response_time = 0;
    p.tilt_limit = 0.6;
    Simulation sim(test::flatFloor(30, 30, 0.01, p));
    std::vector<Event> impacts;
    while (sim.time() < 0.2) {
      if (sim.time() >= 0.03 - 1e-12) sim.setTargetTilt(0.5, 0);
      sim.step();
      for (const Event& event : sim.events()) impacts.push_back(event);
    }
    return impacts;
  };
  const double g = Params().gravity, up = w * y * (1 + e);
  const auto above = [&](double s) {
    const double z = kRadius + up * s - 0.5 * g * s * s;
    return -y * std::sin(w * s) + z * std::cos(w * s) - kRadius;
  };
  double lo = 0.005, hi = 0.02;  // above(lo) > 0 > above(hi)
  for (int i = 0; i < 100; ++i) (above(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
  const double flight = lo;  // 10.19 ms
  const std::vector<Event> fine = kick(1e-4);
  ASSERT_EQ(fine.size(), 3u);
  EXPECT_NEAR(fine[1].time - fine[0].time, flight, 1e-9);
  for (double step : {0.01, 0.02}) {
    const std::vector<Event> coarse = kick(step);
    ASSERT_EQ(coarse.size(), 3u) << "step " << step;
    // The landing to 1e-9 s (the sweep's quadratic, off by 2.2e-7 s, is corrected on the true
    // path); the bounce after it, on the 0.1 ms run's, to 2e-5 s.
    EXPECT_NEAR(coarse[1].time - coarse[0].time, flight, 1e-9) << "step " << step;
    EXPECT_NEAR(coarse[2].time - coarse[0].time, fine[2].time - fine[0].time, 2e-5);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(coarse[k].speed, fine[k].speed, 0.01 * fine[k].speed) << "step " << step;
  }
}

TEST(Impact, AHundredMetresPerSecondNeverTunnelsThroughAFiveMillimetreWall) {
  const AxisSlots x(0.005, 0.0221, 11), y(0.005, 0.0221, 3), z(0.005, 0.012, 2);
  Maze maze = test::floorMaze(x, y, z);
  for (int j = 0; j < 3; ++j) maze.setSolid({6, j, 1}, true);  // a 5 mm wall mid-board
  const double wall = x.lower(6) - maze.pivot().x();           // its -x face, board frame
  for (double angle : {0.0, 0.4, 1.2}) {
    const Vec3 v = 100 * Vec3(std::cos(angle), std::sin(angle) * 0.01, 0);
    Params p = placed(model(Model::Smooth, 0.7), {wall - 0.05, 0, kRadius}, v);
    Simulation sim({maze, p});
    double max_x = -1;
    for (int i = 0; i < 100; ++i) {
      sim.step();
      max_x = std::max(max_x, sim.marbleInBoard().x());
    }
    EXPECT_LE(max_x, wall - kRadius + 1e-9) << "angle " << angle;
  }
}

TEST(Impact, ElasticImpactsAtWallsEdgesAndCornersNeverAddEnergy) {
  // e = 1 and no friction: every impact, alone or several at once, may only keep the energy
  // (contacts slower than the bounce threshold lose a little). Throws in all directions from
  // the classic maze's start, which runs into walls, posts, edges and corners.
  Scene scene = loadScene("classic");
  scene.params.model = Model::Smooth;
  scene.params.restitution = 1.0;
  int impacts = 0;
  for (int k = 0; k < 24; ++k) {
    const double angle = 2 * kPi * k / 24;
    Simulation sim(scene);
    sim.placeMarble(sim.startInBoard() + Vec3(0, 0, 0.004),
                    {1.5 * std::cos(angle), 1.5 * std::sin(angle), 0.3});
    const double energy0 = sim.energy();
    double rise = 0;
    while (sim.time() < 1.5 && sim.marble().phase == MarblePhase::Free) {
      sim.step();
      rise = std::max(rise, sim.energy() - energy0);
      impacts += static_cast<int>(sim.events().size());
    }
    EXPECT_LE(rise, 1e-9 * energy0) << "throw " << k;  // J
  }
  EXPECT_GT(impacts, 50);  // the throws did meet walls, posts, edges and corners
}

TEST(Impact, SimultaneousImpactsThatNewtonsLawWouldMakeGainEnergyKeepItInstead) {
  // Two walls 80 degrees apart struck at once, e = 1, no friction: restitution taken contact by
  // contact would send the marble off faster than it came (each wall's bounce drives it into
  // the other), so the impacts leave at the largest restitution that adds no energy: the marble
  // leaves both walls, as fast as it came (to 1e-8). One of the walls alone gives the elastic
  // bounce.
  Params p;
  p.model = Model::Smooth;
  p.restitution = 1.0;
  ContactSolver solver(p);
  std::vector<Contact> walls(2);
  walls[0].normal = Vec3(1, 0, 0);
  walls[1].normal = Vec3(std::cos(80 * kPi / 180), std::sin(80 * kPi / 180), 0);
  for (Contact& c : walls) c.grid_point = c.surface_velocity = Vec3::Zero();
  const Vec3 approach = -Vec3(std::cos(10 * kPi / 180), std::sin(10 * kPi / 180), 0);
  Velocities body;
  body.linear = approach;
  std::vector<ContactOutcome> outcomes;
  solver.impact(walls, &body, &outcomes);
  EXPECT_LE(body.linear.norm(), 1.0 + 1e-12);
  EXPECT_NEAR(body.linear.norm(), 1.0, 1e-8);
  for (const Contact& wall : walls) EXPECT_GE(body.linear.dot(wall.normal), -1e-12);
  ASSERT_EQ(outcomes.size(), 2u);
  EXPECT_TRUE(outcomes[0].bounce && outcomes[1].bounce);  // both were impacts
  Velocities alone;
  alone.linear = approach;
  solver.impact({walls[0]}, &alone, &outcomes);
  EXPECT_NEAR(alone.linear.x(), -approach.x(), 1e-12);  // e = 1 off one wall
  EXPECT_NEAR(alone.linear.norm(), 1.0, 1e-12);
}

TEST(Impact, AFloorAndAWallStruckAtOnceWithFrictionRespondContinuouslyInE) {
  // A marble flying into the foot of a wall (1 m/s along x, falling at 0.14 m/s) meets the floor
  // and the wall in one instant. With friction, e = 1 at both would turn its spin up and add
  // 0.8% of its energy; taken as perfectly inelastic instead, it stopped dead at e = 1 where at
  // e = 0.99 it came back at 0.99 m/s. Now it comes back nearly as fast at e = 1 as at 0.99,
  // and never with more energy than it came with.
  const auto rebound = [](double e) {
    Params p;
    p.restitution = e;
    ContactSolver solver(p);
    std::vector<Contact> contacts(2);
    contacts[0].normal = Vec3(0, 0, 1);   // the floor
    contacts[1].normal = Vec3(-1, 0, 0);  // the wall
    for (Contact& c : contacts) c.grid_point = c.surface_velocity = Vec3::Zero();
    Velocities body;
    body.linear = Vec3(1, 0, -0.14);
    std::vector<ContactOutcome> outcomes;
    solver.impact(contacts, &body, &outcomes);
    const double m = p.marbleMass(), I = p.marbleInertia();
    const double before = 0.5 * m * Vec3(1, 0, -0.14).squaredNorm();
    const double after = 0.5 * m * body.linear.squaredNorm() + 0.5 * I * body.angular.squaredNorm();
    EXPECT_LE(after, before * (1 + 1e-12)) << "e " << e;
    return body.linear;
  };
  const Vec3 elastic = rebound(1.0), nearly = rebound(0.99);
  EXPECT_LT(elastic.x(), -0.95);
  EXPECT_GE(elastic.z(), 0);
  EXPECT_NEAR(elastic.x(), nearly.x(), 0.02);
}

TEST(Impact, TwoContactsAtRightAnglesAreSolvedExactly) {
  // A marble on the floor against a wall (normals z and x), a board at rest. Pressed into both
  // by a step of gravity across the groove, it stops dead: both contacts stick. Rolling along
  // the groove as well, the floor keeps it rolling without slip and the wall's friction slides:
  // the floor's contact point does not move, neither normal approaches. Exact to rounding,
  // where the sweeps stop short (they converge by a factor of 0.15 to 0.4 a sweep).
  Params p;
  ContactSolver solver(p);
  std::vector<Contact> groove(2);
  groove[0].normal = Vec3(0, 0, 1);
  groove[1].normal = Vec3(1, 0, 0);
  for (Contact& c : groove) c.grid_point = c.surface_velocity = Vec3::Zero();
  Velocities body;
  body.linear = Vec3(-0.004, 0, -0.0098);  // a step of a tilted board's gravity
  std::vector<ContactOutcome> outcomes;
  solver.constrain(groove, &body, &outcomes);
  EXPECT_LT(body.linear.norm(), 1e-16);
  EXPECT_LT(body.angular.norm() * p.marble_radius, 1e-16);
  body.linear = Vec3(-0.004, 0.3, -0.0098);  // and rolling along the groove
  body.angular = Vec3(-0.3 / p.marble_radius, 0, 0);
  solver.constrain(groove, &body, &outcomes);
  const Vec3 floor_point = body.linear + body.angular.cross(-p.marble_radius * groove[0].normal);
  EXPECT_LT(floor_point.norm(), 1e-15);      // rolls on the floor without slip
  EXPECT_NEAR(body.linear.x(), 0, 1e-16);    // no approach to the wall
  EXPECT_NEAR(body.linear.z(), 0, 1e-16);    // nor to the floor
  EXPECT_GT(outcomes[1].normal_impulse, 0);  // the wall presses
  EXPECT_LT(body.linear.y(), 0.3);           // and its friction slows the marble
  EXPECT_GT(body.linear.y(), 0.29);
}

TEST(Impact, AFloorAndAWallOneSlippingKeepToCoulombsLaw) {
  // A marble rolling along the foot of a wall, pressed into it and the floor, on a board at rest
  // and on one turning, the groove at any angle in the world: whatever the pair solver takes its
  // frictions from (a closed form where the slip across the groove is nil or rounding's, as the
  // surfaces of one rigid board leave it, Newton's method elsewhere), each contact must keep to
  // its law. Neither normal approaches; a contact that sticks leaves no slip, its friction
  // within its cone; one that slips is held back by mu times its normal impulse, against its
  // slip. The frictions are read back from the velocities' changes (impulse and angular impulse)
  // with the solver's normal impulses.
  std::mt19937_64 random(23);
  std::uniform_real_distribution<double> unit(-1, 1);
  const auto vec = [&](double size) -> Vec3 {
    return Vec3(unit(random), unit(random), unit(random)) * size;
  };
  Params p;
  ContactSolver solver(p);
  const double m = p.marbleMass(), I = p.marbleInertia(), r = p.marble_radius, mu = p.friction;
  int slipping = 0, across = 0;
  for (int k = 0; k < 20000; ++k) {
    const Mat3 turn = Eigen::AngleAxisd(kPi * unit(random), vec(1).normalized()).toRotationMatrix();
    const Vec3 floor = turn * Vec3::UnitZ(), wall = turn * Vec3::UnitX(), along = floor.cross(wall);
    // A board at rest, or one turning at up to 1.7 rad/s about a pivot some centimetres away.
    const Vec3 spin = k % 2 ? Vec3(Vec3::Zero()) : vec(1), centre = vec(0.1);
    std::vector<Contact> groove(2);
    groove[0].normal = floor;
    groove[1].normal = wall;
    for (Contact& c : groove) c.surface_velocity = spin.cross(centre - r * c.normal);
    // Surfaces that do not move as one (an impact's, met at a tile's point, need not) leave a
    // slip across the groove that no friction changes, and Newton's method finds the frictions:
    // up to 1 mm/s, and in a sixth of the pairs up to 3 cm/s under a marble crawling at 3 mm/s.
    if (k % 3 == 0) groove[1].surface_velocity += (k % 6 ? 0.001 : 0.03) * unit(random) * floor;
    // Rolling along the groove at 0.05 to 0.5 m/s, slipping on the floor by up to 0.17 mm/s, and
    // pressed into the floor harder than into the wall (up to a step of gravity): the floor's
    // friction stops its slip and the wall's against the roll, which the wall's cannot: the
    // floor sticks and the wall slips, the case the pair solver answers (both slipping is the
    // sweeps').
    const double speed =
        (k % 4 < 2 ? 1 : -1) * (k % 6 ? 0.05 + 0.45 * std::abs(unit(random)) : 0.003);
    Velocities body;
    body.linear = spin.cross(centre) + speed * along -
                  (0.004 + 0.006 * std::abs(unit(random))) * floor -
                  (0.001 + 0.002 * std::abs(unit(random))) * wall;
    body.angular = spin + floor.cross(speed * along) / r + vec(0.0001 / r);
    const Velocities before = body;
    std::vector<ContactOutcome> outcomes;
    solver.constrain(groove, &body, &outcomes);
    // The frictions, f_floor across the floor's normal and f_wall across the wall's:
    // m dv = N_floor floor + N_wall wall + f_floor + f_wall, I dw = -r (floor x f_floor + wall x
    // f_wall). In the groove's frame (floor z, wall x, along y) they are its components.
    const Vec3 impulse = turn.transpose() * (m * (body.linear - before.linear));
    const Vec3 turning = turn.transpose() * (I * (body.angular - before.angular)) / r;
    const double N_floor = outcomes[0].normal_impulse, N_wall = outcomes[1].normal_impulse;
    const Vec3 f_floor = turn * Vec3(impulse.x() - N_wall, turning.x(), 0);
    const Vec3 f_wall = turn * Vec3(0, -turning.z(), impulse.z() - N_floor);
    ASSERT_GT(N_floor, 0) << k;
    ASSERT_GT(N_wall, 0) << k;
    // The two components the frictions were not read from must agree with them: the impulse
    // along the groove, and the angular impulse about it.
    const double impulses = N_floor + N_wall;
    EXPECT_NEAR(impulse.y(), turning.x() - turning.z(), 1e-10 * impulses) << k;
    EXPECT_NEAR(turning.y(), (impulse.z() - N_floor) - (impulse.x() - N_wall), 1e-10 * impulses)
        << k;
    const auto slip = [&](const Contact& c) {
      const Vec3 s = body.linear + body.angular.cross(-r * c.normal) - c.surface_velocity;
      return Vec3(s - s.dot(c.normal) * c.normal);
    };
    for (int i = 0; i < 2; ++i) {
      const Contact& c = groove[i];
      const Vec3 f = i == 0 ? f_floor : f_wall;
      const double N = outcomes[i].normal_impulse;
      EXPECT_NEAR((body.linear - c.surface_velocity).dot(c.normal), 0, 1e-15) << k;
      const Vec3 s = slip(c);
      if (s.norm() <= 1e-14) {  // sticks (m/s)
        EXPECT_LE(f.norm(), mu * N * (1 + 1e-9)) << k;
        continue;
      }
      ++slipping;
      EXPECT_NEAR(f.norm(), mu * N, 1e-9 * mu * N) << k << " contact " << i;
      EXPECT_LT(f.dot(s), -(1 - 1e-9) * f.norm() * s.norm()) << k << " contact " << i;
    }
    across += std::abs(slip(groove[1]).dot(floor)) > 1e-6;
  }
  EXPECT_GT(slipping, 5000);
  EXPECT_GT(across, 1000);
  EXPECT_GE(solver.pairCounts().solves, 20000u);  // each pair went to the Newton branch
}

TEST(Impact, ThreeContactsAtRightAnglesAreSolvedExactly) {
  // A marble wedged in a corner (the floor and two walls: normals z, x and y) of a board turning
  // at 0.36 rad/s about its pivot, 6 cm away. A step of gravity presses it into all three and it
  // had drifted off the board's motion by a few mm/s and rad/s: all three stick, and it moves
  // rigidly with the board, its velocity the board's at its centre and its spin the board's.
  // Exact to rounding, where the sweeps stop short (they converge by a factor of 0.15 to 0.4 a
  // sweep: here 1.5e-9 m/s and 2.5e-9 m/s at the surface off after 8).
  Params p;
  ContactSolver solver(p);
  const Vec3 board_spin(0.3, -0.2, 0), centre(0.05, 0.04, p.marble_radius);
  std::vector<Contact> corner(3);
  corner[0].normal = Vec3(0, 0, 1);
  corner[1].normal = Vec3(1, 0, 0);
  corner[2].normal = Vec3(0, 1, 0);
  for (Contact& c : corner) {
    c.surface_velocity = board_spin.cross(centre - p.marble_radius * c.normal);
  }
  Velocities body;
  body.linear = board_spin.cross(centre) + Vec3(-0.004, -0.003, -0.0098);
  body.angular = board_spin + Vec3(0.2, -0.5, 0.3);
  std::vector<ContactOutcome> outcomes;
  solver.constrain(corner, &body, &outcomes);
  EXPECT_LT((body.linear - board_spin.cross(centre)).norm(), 1e-15);
  EXPECT_LT((body.angular - board_spin).norm() * p.marble_radius, 1e-15);
  for (const ContactOutcome& o : outcomes) EXPECT_GT(o.normal_impulse, 0);  // all three press
}

TEST(Impact, OneContactIsConstrainedAsTheSweepsSolveItToTheBit) {
  // constrain() solves one contact directly (a marble rolling on a floor: most steps); impact()
  // still takes it through the Gauss-Seidel sweeps. Below the bounce threshold both ask the
  // same of it (leave at zero normal speed, friction within its cone), so they must agree to
  // the bit: velocities, impulse and the surface's work. Over normals of faces and of edges and
  // corners, moving surfaces, marbles pressing, leaving, sticking and slipping, both models.
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> unit(-1, 1);
  const auto vec = [&](double size) -> Vec3 {  // (a Vec3: not an expression of a temporary)
    return Vec3(unit(random), unit(random), unit(random)) * size;
  };
  int slipping = 0, sticking = 0, leaving = 0;
  for (int k = 0; k < 20000; ++k) {
    Params p;
    p.model = k % 5 == 0 ? Model::Smooth : Model::Rolling;
    p.friction = k % 7 == 0 ? 0.0 : 0.3;
    ContactSolver solver(p);
    std::vector<Contact> one(1);
    const Vec3 face = Vec3::Unit(k % 3) * (k % 2 ? 1 : -1);
    one[0].normal = k % 4 == 0 ? vec(1).normalized() : face;
    one[0].surface_velocity = k % 3 == 0 ? Vec3(Vec3::Zero()) : vec(0.05);
    Velocities body{vec(0.5), vec(0.5 / p.marble_radius)};
    // Its normal speed relative to the surface within the bounce threshold either way.
    const Vec3& n = one[0].normal;
    const double away = (body.linear - one[0].surface_velocity).dot(n);
    body.linear += (unit(random) * 0.9 * p.bounceThreshold() - away) * n;
    // Half of them nearly rolling on the surface (slipping at up to some mm/s), where friction
    // can stop the slip.
    if (k % 2)
      body.angular = n.cross(body.linear - one[0].surface_velocity) / p.marble_radius +
                     vec(0.002 / p.marble_radius);
    Velocities direct = body, swept = body;
    std::vector<ContactOutcome> direct_outcomes, swept_outcomes;
    solver.constrain(one, &direct, &direct_outcomes);
    const double direct_work = solver.surfaceWork();
    solver.impact(one, &swept, &swept_outcomes);
    ASSERT_FALSE(swept_outcomes[0].bounce) << k;
    ASSERT_EQ(direct.linear, swept.linear) << k;
    ASSERT_EQ(direct.angular, swept.angular) << k;
    ASSERT_EQ(direct_outcomes[0].normal_impulse, swept_outcomes[0].normal_impulse) << k;
    ASSERT_EQ(direct_work, solver.surfaceWork()) << k;
    if (direct_outcomes[0].normal_impulse == 0) {
      ++leaving;
    } else if (p.model == Model::Rolling && p.friction > 0) {
      const Vec3 slip =
          direct.linear + direct.angular.cross(-p.marble_radius * n) - one[0].surface_velocity;
      ++((slip - slip.dot(n) * n).norm() < 1e-12 ? sticking : slipping);
    }
  }
  // Each branch of the solve was taken often.
  EXPECT_GT(leaving, 1000);
  EXPECT_GT(sticking, 1000);
  EXPECT_GT(slipping, 1000);
}

// --- Rolling resistance and drag ---------------------------------------------------------------

TEST(Resistance, RollingResistanceDeceleratesAtFiveSeventhsCrrG) {
  // A rolling sphere under a resisting torque c_rr N r: a = -(5/7) c_rr g.
  Params p = placed(model(Model::Rolling), {-0.9, 0, kRadius}, {0.5, 0, 0});
  p.rolling_resistance = 0.01;
  Simulation sim(test::flatFloor(200, 10, 0.01, p));
  sim.placeMarble(p.start_position, p.start_velocity, {0, 0.5 / kRadius, 0});  // rolling
  run(&sim, 2.0);
  const double expected = 0.5 - 5.0 / 7.0 * 0.01 * 9.81 * 2.0;
  EXPECT_NEAR(sim.marble().velocity.x(), expected, 0.005 * expected);  // 0.5%
}

TEST(Resistance, QuadraticAirDragSlowsAsOneOverOnePlusKVT) {
  // Free flight without gravity under F = -1/2 rho C_d A |v| v: v(t) = v0 / (1 + k v0 t), with
  // k = rho C_d A / (2 m).
  const Params p = test::dragFlight(model(Model::Smooth));
  Simulation sim(test::flatFloor(10, 10, 0.01, p));
  run(&sim, 1.0);
  const double expected = test::dragFlightSpeed(p, 1.0);
  EXPECT_NEAR(sim.marble().velocity.x(), expected, 0.001 * expected);  // 0.1%
  EXPECT_LT(expected, 45);  // the drag matters at this speed: the test can tell it from none
}

// --- Extremes -----------------------------------------------------------------------------------

/// The lowest the marble's centre gets below resting height on the floor, in the board frame.
double deepestSink(Simulation* sim, int steps) {
  double deepest = 0;
  for (int i = 0; i < steps && sim->marble().phase == MarblePhase::Free; ++i) {
    sim->step();
    deepest = std::max(deepest, kRadius - sim->marbleInBoard().z());
  }
  EXPECT_EQ(sim->marble().phase, MarblePhase::Free);
  return deepest;
}

TEST(Extremes, ABoardTurningAwayFastCarriesTheMarbleWithoutLettingItSink) {
  for (double step : {0.001, 0.01}) {
    Params p = placed(model(Model::Rolling), {0.12, 0, kRadius});
    p.step = step;
    p.tilt_rate_limit = 0;
    p.tilt_limit = 1.0;
    Simulation sim(test::flatFloor(40, 10, 0.01, p));
    sim.setTiltRate(0, 2.0);  // the +x end, under the marble, drops at 0.24 m/s
    EXPECT_LT(deepestSink(&sim, static_cast<int>(0.2 / step)), 1e-6) << "step " << step;  // m
  }
}

TEST(Extremes, ABoardSnappingToATiltNeverPushesTheMarbleThroughTheFloor) {
  for (double target : {-0.17, 0.17}) {
    Params p = placed(model(Model::Smooth), {0.05, 0, kRadius});
    p.tilt_rate_limit = 0;
    p.tilt_response_time = 0;  // the whole tilt in one step: 170 rad/s
    Simulation sim(test::flatFloor(40, 10, 0.01, p));
    sim.setTargetTilt(0, target);
    EXPECT_LT(deepestSink(&sim, 300), 1e-6) << "pitch " << target;  // m
  }
}

TEST(Extremes, AMarbleLeavingTheFloorAtALongStepNeverEndsInIt) {
  for (double step : {0.001, 0.02, 0.1}) {
    Params p = placed(model(Model::Smooth), {0, 0, kRadius + 3e-7}, {0, 0, 0.008});
    p.step = step;
    Simulation sim(test::flatFloor(10, 10, 0.01, p));
    EXPECT_LT(deepestSink(&sim, 20), 1e-6) << "step " << step;  // m
  }
}

// --- Holes and the goal ----------------------------------------------------------------------

TEST(Finish, AHoleSwallowsTheMarbleAndIsReported) {
  const AxisSlots x(0.005, 0.0221, 9), y(0.005, 0.0221, 3), z(0.005, 0.012, 2);
  Maze maze = test::floorMaze(x, y, z);
  maze.setSolid({5, 1, 0}, false);  // a hole
  Params p =
      placed(model(Model::Rolling), {x.centre(1) - maze.pivot().x(), 0, kRadius}, {0.2, 0, 0});
  Simulation sim({maze, p});
  bool reported = false;
  while (sim.time() < 2 && !reported) {
    sim.step();
    for (const Event& e : sim.events())
      if (e.kind == EventKind::Hole) {
        reported = true;
        EXPECT_EQ(e.tile, Index3(5, 1, 0));
      }
  }
  EXPECT_TRUE(reported);
  EXPECT_EQ(sim.marble().phase, MarblePhase::InHole);
  const Vec3 held = sim.marbleInBoard();
  run(&sim, 0.5);
  EXPECT_NEAR((sim.marbleInBoard() - held).norm(), 0, 1e-12);  // stays in the hole
}

TEST(Finish, ReachingTheGoalIsReported) {
  const AxisSlots x(0.005, 0.0221, 9), y(0.005, 0.0221, 3), z(0.005, 0.012, 2);
  Maze maze = test::floorMaze(x, y, z);
  maze.addGoal({7, 1});
  Params p =
      placed(model(Model::Rolling), {x.centre(1) - maze.pivot().x(), 0, kRadius}, {0.3, 0, 0});
  Simulation sim({maze, p});
  while (sim.time() < 2 && sim.marble().phase == MarblePhase::Free) sim.step();
  ASSERT_EQ(sim.events().size(), 1u);
  EXPECT_EQ(sim.events()[0].kind, EventKind::Goal);
  EXPECT_EQ(sim.events()[0].tile, Index3(7, 1, 0));
  EXPECT_EQ(sim.marble().phase, MarblePhase::AtGoal);
}

// --- Board -----------------------------------------------------------------------------------

TEST(Board, TiltIsClampedToTheLimitAndRateLimited) {
  Params p;
  p.tilt_limit = 0.1;
  p.tilt_rate_limit = 1.0;
  p.tilt_response_time = 0;  // straight to the target, as fast as the rate limit allows
  Board board(p);
  board.setTargetTilt(0.5, -0.5);
  board.advance(0.01);
  EXPECT_NEAR(board.roll(), 0.01, 1e-12);  // 1 rad/s for 10 ms
  EXPECT_NEAR(board.pitch(), -0.01, 1e-12);
  EXPECT_NEAR(board.angularVelocity().norm(), std::sqrt(2.0), 1e-3);
  for (int i = 0; i < 100; ++i) board.advance(0.01);
  EXPECT_DOUBLE_EQ(board.roll(), 0.1);
  EXPECT_DOUBLE_EQ(board.pitch(), -0.1);
  EXPECT_EQ(board.angularVelocity(), Vec3::Zero());
  board.setTiltRate(-5.0, 0);  // clamped to 1 rad/s
  board.advance(0.01);
  EXPECT_NEAR(board.roll(), 0.09, 1e-12);
}

TEST(Board, FollowsATargetLikeAFirstOrderServo) {
  Params p;
  p.tilt_rate_limit = 0;  // the lag alone
  p.tilt_response_time = 0.05;
  Board board(p);
  board.setTargetTilt(0.1, 0);
  for (int i = 0; i < 50; ++i) board.advance(0.001);  // one time constant
  EXPECT_NEAR(board.roll(), 0.1 * (1 - std::exp(-1.0)), 1e-12);
  for (int i = 0; i < 2000; ++i) board.advance(0.001);
  EXPECT_DOUBLE_EQ(board.roll(), 0.1);  // comes to rest on the target
  EXPECT_EQ(board.angularVelocity(), Vec3::Zero());
}

TEST(Board, RotationIsRollThenPitchAboutFixedAxes) {
  const Mat3 r = Board::rotationFor(0.2, 0.3);
  const Mat3 expected = Eigen::AngleAxisd(0.3, Vec3::UnitY()).toRotationMatrix() *
                        Eigen::AngleAxisd(0.2, Vec3::UnitX()).toRotationMatrix();
  EXPECT_NEAR((r - expected).norm(), 0, 1e-15);
  // Positive pitch lowers the +x end (REP 103, right hand about +y).
  EXPECT_LT((r * Vec3::UnitX()).z(), 0);
}

// --- Determinism -----------------------------------------------------------------------------

TEST(Determinism, TheSameInputsGiveBitIdenticalStates) {
  auto trajectory = [] {
    Scene scene = loadScene("classic");
    Simulation sim(scene);
    std::vector<double> values;
    for (int i = 0; i < 3000; ++i) {
      sim.setTargetTilt(0.1 * std::sin(i * 0.003), 0.1 * std::cos(i * 0.002));
      sim.step();
      for (int a = 0; a < 3; ++a) values.push_back(sim.marble().position[a]);
    }
    return values;
  };
  EXPECT_EQ(trajectory(), trajectory());
}

}  // namespace
}  // namespace marble_maze
