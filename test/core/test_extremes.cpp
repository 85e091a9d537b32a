// Numerical stability at the extremes a user can reach with --set and the maze format, each with
// its bound: steps from 1e-6 to 0.05 s, e = 0 and e = 1, a marble in a corner at any tilt, and
// the settings that cannot be simulated refused with a message naming the key.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "marble_maze/maze_file.h"
#include "marble_maze/simulation.h"
#include "scenes.h"

namespace marble_maze {
namespace {

using test::placed;

constexpr double kRadius = 0.006;
const IntegratorKind kAll[] = {IntegratorKind::SemiImplicitEuler, IntegratorKind::VelocityVerlet,
                               IntegratorKind::RungeKutta4};

using test::name;

/// The deepest each scheme lets the marble into a tile, as a share of its radius ("Where it
/// holds" in the README): semi-implicit Euler's velocity lags half a step behind its position,
/// and a marble wedged between a floor and a wall of a board turning under it goes further in.
double mostPenetration(IntegratorKind integrator) {
  return integrator == IntegratorKind::SemiImplicitEuler ? 0.02 : 0.01;
}

Params with(IntegratorKind integrator, Model model, double step) {
  return test::scheme(integrator, model, step, Params().restitution);
}

/// How far the marble is inside any tile now (0 when it overlaps none).
double penetration(const Simulation& sim) {
  std::vector<Contact> contacts;
  findContacts(sim.maze(), sim.gridFrame(), sim.marble().position, kRadius, 0, &contacts);
  double deepest = 0;
  for (const Contact& c : contacts) deepest = std::max(deepest, c.depth);
  return deepest;
}

TEST(Extremes,
     EveryStepFromAMicrosecondToFiftyMillisecondsStaysFiniteOutOfTheTilesAndGainsNoEnergy) {
  // A drop onto a 10 degree incline: flight, a bounce, then rolling or sliding down it.
  for (IntegratorKind integrator : kAll)
    for (Model model : {Model::Rolling, Model::Smooth})
      for (double step : {1e-6, 1e-4, 1e-3, 1e-2, 0.05}) {
        Params p = placed(with(integrator, model, step), {-0.5, 0, kRadius + 0.01});
        p.initial_pitch = 0.17;
        Simulation sim(test::flatFloor(120, 10, 0.01, p));
        const double energy0 = sim.energy();
        const int steps = static_cast<int>(std::min(20000.0, std::round(1.0 / step)));
        double deepest = 0, rise = 0;
        for (int i = 0; i < steps && sim.marble().phase == MarblePhase::Free; ++i) {
          sim.step();
          ASSERT_TRUE(sim.marble().position.allFinite() && sim.marble().velocity.allFinite())
              << name(p) << " step " << i;
          deepest = std::max(deepest, penetration(sim));
          rise = std::max(rise, sim.energy() - energy0);
        }
        EXPECT_EQ(sim.marble().phase, MarblePhase::Free) << name(p);
        EXPECT_LE(deepest, 0.01 * kRadius) << name(p);         // 1% of the radius
        EXPECT_LE(rise, 1e-9 * std::abs(energy0)) << name(p);  // a board at rest does no work
      }
}

TEST(Extremes, AirDragOnAFeatherLightMarbleAtLongStepsNeverGainsEnergy) {
  // A marble of 1 kg/m^3 (a soap bubble's density) under drag of C_d 1, dropped from 5 cm: its
  // speed is at most 0.36 m/s, reached within a few ms. At a 0.1 s step one substep slowed it
  // by 2.7 times its speed, overshot and grew it to 1e18 m/s; steps are cut to keep it stable.
  for (IntegratorKind integrator : kAll)
    for (double step : {1e-3, 0.1}) {
      Params p = placed(with(integrator, Model::Rolling, step), {0, 0, kRadius + 0.05});
      p.drag_coefficient = 1;
      p.marble_density = 1;
      Simulation sim(test::flatFloor(20, 20, 0.01, p));
      const double energy0 = sim.energy();
      double rise = 0;
      for (int i = 0; i < std::lround(2.0 / step); ++i) {
        sim.step();
        ASSERT_TRUE(sim.marble().velocity.allFinite()) << name(p) << " step " << i;
        rise = std::max(rise, sim.energy() - energy0);
      }
      EXPECT_LE(rise, 1e-9 * std::abs(energy0)) << name(p);
      EXPECT_EQ(sim.marble().phase, MarblePhase::Free) << name(p);
      // At rest on the floor: within the contact margin, 1e-7 m, which holds a marble there.
      EXPECT_NEAR(sim.marbleInBoard().z(), kRadius, 1e-7) << name(p);
      EXPECT_LT(sim.marble().velocity.norm(), 1e-6) << name(p);
    }
}

TEST(Extremes, ADeadImpactStopsTheMarbleWithoutJitter) {
  for (IntegratorKind integrator : kAll)
    for (double step : {1e-3, 1e-2, 0.05}) {
      Params p = placed(with(integrator, Model::Smooth, step), {0, 0, kRadius + 0.02});
      p.restitution = 0;
      Simulation sim(test::flatFloor(10, 10, 0.01, p));
      int impacts = 0;
      bool landed = false;
      double jitter = 0;
      for (int i = 0; i < static_cast<int>(2.0 / step); ++i) {
        sim.step();
        impacts += static_cast<int>(sim.events().size());
        landed = landed || sim.marble().position.z() < kRadius + 1e-6;
        if (landed) jitter = std::max(jitter, std::abs(sim.marble().velocity.z()));
      }
      // One impact (at a coarse step semi-implicit Euler's threshold of 2 g h takes it as a
      // contact: none), then nothing.
      EXPECT_LE(impacts, 1) << name(p);
      EXPECT_TRUE(landed) << name(p);
      EXPECT_LT(jitter, 1e-9) << name(p);  // m/s
    }
}

TEST(Extremes, AMarbleInACornerRestsAtAnyTilt) {
  // The classic maze's start is a corner (walls at -x and +y): tilted towards it the marble is
  // pressed into it, and must rest there, moving less than a micrometre in 5 s.
  for (IntegratorKind integrator : kAll)
    for (double degrees : {10.0, 30.0, 45.0, 60.0, 80.0, 89.0}) {
      Scene scene = loadScene("classic");
      scene.params.integrator = integrator;
      scene.params.tilt_limit = 1.57;
      const double tilt = degrees * 3.14159265358979323846 / 180;
      scene.params.initial_roll = -tilt / std::sqrt(2.0);   // negative roll lowers +y
      scene.params.initial_pitch = -tilt / std::sqrt(2.0);  // lowers -x
      Simulation sim(scene);
      sim.setTargetTilt(scene.params.initial_roll, scene.params.initial_pitch);
      for (int i = 0; i < 3000; ++i) sim.step();  // settle
      const Vec3 settled = sim.marbleInBoard();
      for (int i = 0; i < 5000; ++i) sim.step();
      EXPECT_LT((sim.marbleInBoard() - settled).norm(), 1e-6)
          << getParam(scene.params, "integrator") << " at " << degrees << " degrees";
      EXPECT_LT(sim.marble().velocity.norm(), 1e-6);
    }
}

TEST(Extremes, TiltsSnappingBetweenEightySixDegreesNeverLetTheMarbleOutOfAClosedRoom) {
  // A room of 0.1 m cells with a floor, walls and a lid; the target tilt jumps between +-1.2,
  // +-1.45 or +-1.5 rad on both axes with no servo lag and no rate limit (the board snaps across
  // its range in one step), every 0.3 s, and as rate spikes: reversing at every step. At every step
  // up to 0.05 s the marble stays in the room, finite. Built in code so that its goal can be out of
  // reach (inside a wall): the marble plays on.
  Maze room(AxisSlots::uniform(0.1, 5), AxisSlots::uniform(0.1, 5), AxisSlots::uniform(0.1, 4));
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i)
        room.setSolid({i, j, k}, k == 0 || k == 3 || i == 0 || j == 0 || i == 4 || j == 4);
  room.setStart({2, 2});
  room.addGoal({0, 0});
  for (IntegratorKind integrator : kAll)
    for (Model model : {Model::Rolling, Model::Smooth})
      for (double step : {0.001, 0.01, 0.05})
        for (double period : {0.25, 0.3, step})
          for (double amplitude : {1.2, 1.45, 1.5}) {
            Scene scene{room, Params()};
            scene.params.integrator = integrator;
            scene.params.model = model;
            scene.params.step = step;
            scene.params.tilt_limit = 1.5;
            scene.params.tilt_rate_limit = 0;
            scene.params.tilt_response_time = 0;
            Simulation sim(scene);
            // Inside: the room's cells are grid slots 1..3 on each axis, 0.1..0.4 m; board frame is
            // the grid less the pivot (0.25, 0.25, 0.1).
            double outside = 0, free_until = 0;
            for (int i = 0; i < static_cast<int>(2.0 / step); ++i) {
              const int jump = static_cast<int>(i * step / period + 1e-9);
              const double sign = jump % 2 == 0 ? 1 : -1;
              sim.setTargetTilt(amplitude * sign, (jump % 4 < 2 ? amplitude : -amplitude));
              sim.step();
              ASSERT_TRUE(sim.marble().position.allFinite()) << name(scene.params);
              ASSERT_NE(sim.marble().phase, MarblePhase::OffBoard)
                  << name(scene.params) << " at " << i;
              if (sim.marble().phase == MarblePhase::Free) free_until = sim.time();
              const Vec3 g = sim.marbleInBoard() + sim.maze().pivot();
              for (int a = 0; a < 3; ++a)
                outside = std::max({outside, 0.1 + kRadius - g[a], g[a] - (0.4 - kRadius)});
            }
            const std::string what = name(scene.params) + " period " + std::to_string(period) +
                                     " amplitude " + std::to_string(amplitude);
            EXPECT_LE(outside, mostPenetration(integrator) * kRadius) << what;
            EXPECT_EQ(free_until, sim.time()) << what;  // free all along
          }
}

TEST(Extremes, AHalfMillimetreMarbleInMetreCellsStaysOutOfTheTilesOfATurningBoard) {
  // 5 x 5 cells of 1 m, walled round, the board swinging by up to 0.6 rad at 1 rad/s: a marble
  // wedged between the floor and a wall 2 m from the pivot, where a board turning 0.03 rad a step
  // moves 120 radii. The board's turn a substep is cut to the marble's size against the board's.
  const double r = 0.0005;
  const int n = 5;
  Maze maze(AxisSlots::uniform(1.0, n), AxisSlots::uniform(1.0, n), AxisSlots::uniform(0.01, 2));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      maze.setSolid({i, j, 0}, true);
      if (i == 0 || j == 0 || i == n - 1 || j == n - 1) maze.setSolid({i, j, 1}, true);
    }
  maze.setStart({2, 2});
  for (IntegratorKind integrator : kAll)
    for (Model model : {Model::Rolling, Model::Smooth})
      for (double step : {0.001, 0.01, 0.05})
        for (double swing : {1.0, 5.0}) {
          Params p = placed(with(integrator, model, step), {0.1, 0.2, r + 0.05});
          p.marble_radius = r;
          p.tilt_limit = 0.6;
          Simulation sim({maze, p});
          double deepest = 0;
          for (int i = 0; i < static_cast<int>(4.0 / step); ++i) {
            const double t = i * step;
            sim.setTargetTilt(0.6 * std::sin(swing * t), 0.6 * std::cos(0.7 * swing * t));
            sim.step();
            if (sim.marble().phase != MarblePhase::Free) break;  // flung over the 1 cm wall
            std::vector<Contact> contacts;
            findContacts(sim.maze(), sim.gridFrame(), sim.marble().position, r, 0, &contacts);
            for (const Contact& c : contacts) deepest = std::max(deepest, c.depth);
          }
          EXPECT_LE(deepest, mostPenetration(integrator) * r) << name(p) << " swing " << swing;
        }
}

TEST(Extremes, ABoardAKilometreFromTheOriginBehavesAsAtTheOrigin) {
  // The classic maze under a circling tilt for 10 s, its pivot at the origin and 1 km away: the
  // physics is worked out around the board, so the marble's path on it is the same to the bit,
  // and in the world it is that path moved by the kilometre (within 1e-6 m).
  const auto play = [](const Vec3& where) {
    Scene scene = loadScene("classic");
    scene.params.board_position = where;
    Simulation sim(scene);
    std::vector<std::pair<Vec3, Vec3>> path;  // on the board, in the world
    for (int i = 0; i < 10000; ++i) {
      const double t = i * 0.001;
      sim.setTargetTilt(0.1 * std::sin(3.1 * t), 0.1 * std::cos(2.3 * t));
      sim.step();
      if (i % 100 == 0) path.emplace_back(sim.marbleInBoard(), sim.worldPosition());
    }
    return path;
  };
  const Vec3 far(1000, -700, 300);
  const auto here = play(Vec3::Zero()), there = play(far);
  double worst = 0;
  for (std::size_t k = 0; k < here.size(); ++k) {
    EXPECT_EQ(here[k].first, there[k].first);  // bit for bit on the board
    worst = std::max(worst, (here[k].second + far - there[k].second).norm());
  }
  EXPECT_LT(worst, 1e-6);                                            // m, in the world
  EXPECT_GT((here.back().first - here.front().first).norm(), 0.01);  // the marble did travel
}

TEST(Extremes, AHundredMetresPerSecondAtWallsEdgesAndCornersNeverTunnelsAndLeavesAtE) {
  // A 5 mm post in a room, hit head on (a face), across its edge and at its corner, at 100 m/s,
  // with each integrator at 1 ms and at the largest step, 50 ms (5 m a step, 800 radii).
  Maze maze(AxisSlots(0.005, 0.5, 5), AxisSlots(0.005, 0.5, 5), AxisSlots(0.005, 0.02, 2));
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) {
      maze.setSolid({i, j, 0}, true);
      if (i == 0 || j == 0 || i == 4 || j == 4 || (i == 2 && j == 2))
        maze.setSolid({i, j, 1}, true);
    }
  maze.setStart({1, 1});
  const Box post = maze.tileBox({2, 2, 1});
  const Vec3 centre = post.centre() - maze.pivot();
  const Vec3 aims[] = {{1, 0, 0}, Vec3(1, 1, 0).normalized(), Vec3(1, 0.999, 0).normalized()};
  for (IntegratorKind integrator : kAll)
    for (double step : {1e-3, 0.05})
      for (const Vec3& aim : aims) {
        Params p = placed(with(integrator, Model::Smooth, step),
                          Vec3(centre.x() - 0.2 * aim.x(), centre.y() - 0.2 * aim.y(), kRadius),
                          100 * aim);
        p.gravity = 0;  // on the floor, touching it without pressing: the impacts alone
        p.restitution = 0.7;
        Simulation sim({maze, p});
        double deepest = 0, fastest = 0;
        std::vector<Event> impacts;
        for (int i = 0; i < 40 && impacts.size() < 2; ++i) {
          sim.step();
          deepest = std::max(deepest, penetration(sim));
          fastest = std::max(fastest, sim.marble().velocity.norm());
          impacts.insert(impacts.end(), sim.events().begin(), sim.events().end());
        }
        ASSERT_GE(impacts.size(), 1u) << name(p);
        EXPECT_EQ(impacts[0].tile, Index3(2, 2, 1)) << name(p);  // the post, not beyond it
        EXPECT_LE(deepest, 0.01 * kRadius) << name(p);
        EXPECT_LE(fastest, 100 * (1 + 1e-12)) << name(p);  // no impact adds speed
        if (aim.y() == 0) {
          ASSERT_GE(impacts.size(), 2u) << name(p);
          // Head on: back from the post at e times 100 m/s, straight onto the room's west wall.
          EXPECT_NEAR(impacts[0].speed, 100, 1e-9 * 100) << name(p);
          EXPECT_NEAR(impacts[1].speed, 70, 1e-9 * 70) << name(p);
        }
      }
}

TEST(Extremes, EveryStepRunsTheClassicMazeUnderATiltProgrammeWithoutEnteringATile) {
  for (IntegratorKind integrator : kAll)
    for (double step : {1e-4, 1e-3, 1e-2, 0.05}) {
      Scene scene = loadScene("classic");
      scene.params.integrator = integrator;
      scene.params.step = step;
      Simulation sim(scene);
      double deepest = 0;
      for (int i = 0; i < static_cast<int>(5.0 / step); ++i) {
        const double t = i * step;
        sim.setTargetTilt(0.1 * std::sin(2 * t), 0.1 * std::cos(2 * t));
        sim.step();
        ASSERT_TRUE(sim.marble().position.allFinite()) << name(scene.params);
        ASSERT_NE(sim.marble().phase, MarblePhase::OffBoard) << name(scene.params);
        if (sim.marble().phase == MarblePhase::Free) deepest = std::max(deepest, penetration(sim));
      }
      EXPECT_LE(deepest, 0.01 * kRadius) << name(scene.params);
    }
}

TEST(Extremes, TheEnergyNeverRisesAboveItsStartPlusTheWorkOfTheTiltingBoard) {
  // The classic maze (holes filled, no goal) under a circling tilt for 5 s, each step from 0.1 to
  // 50 ms: the marble's energy against its start plus what the moving board did through its
  // contacts (here as large as the start, of either sign). The work is taken once a stretch, so
  // where velocity Verlet and RK4 sample the contacts more than once it is approximate: at the
  // coarsest step (ten times the fast preset's) the bound holds to 5% of the start, and to a
  // millionth of it at 10 ms and below.
  for (IntegratorKind integrator : kAll)
    for (double step : {1e-4, 1e-3, 1e-2, 0.05}) {
      Scene scene{test::closedClassic(), with(integrator, Model::Rolling, step)};
      Simulation sim(scene);
      const double energy0 = sim.energy();
      double excess = 0;
      for (int i = 0; i < static_cast<int>(5.0 / step); ++i) {
        const double t = i * step;
        sim.setTargetTilt(0.1 * std::sin(2 * t), 0.1 * std::cos(2 * t));
        sim.step();
        ASSERT_EQ(sim.marble().phase, MarblePhase::Free) << name(scene.params);
        excess = std::max(excess, sim.energy() - energy0 - sim.boardWork());
      }
      EXPECT_LE(excess, (step > 0.01 ? 0.05 : 1e-6) * energy0) << name(scene.params);  // J
    }
}

TEST(Extremes, MarblesFromAHundredthOfACellToLargerThanOneAndSlotsFromATenthOfAMillimetre) {
  // Each on a 10 degree incline for 1 s, rolling into a wall at its foot: finite, never inside a
  // tile by more than 1% of its radius.
  struct Case {
    double thin, wide, radius;
    const char* what;
  };
  const Case cases[] = {{0.1, 0.1, 0.001, "a marble 1% of a 0.1 m cell"},
                        {0.02, 0.02, 0.03, "a marble three cells wide"},
                        {0.0001, 1.0, 0.006, "walls of 0.1 mm between 1 m cells"}};
  for (const Case& c : cases) {
    const int n = 7;
    Maze maze(AxisSlots(c.thin, c.wide, n), AxisSlots(c.thin, c.wide, n), AxisSlots(0.005, 1, 2));
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        maze.setSolid({i, j, 0}, true);
        if (i == 0 || j == 0 || i == n - 1 || j == n - 1) maze.setSolid({i, j, 1}, true);
      }
    maze.setStart({3, 3});
    Params p;
    p.marble_radius = c.radius;
    p.initial_pitch = 0.17;
    p.start_velocity = Vec3(1.0, 0.3, 0);
    Simulation sim({maze, p});
    double deepest = 0;
    for (int i = 0; i < 3000; ++i) {
      sim.step();
      ASSERT_TRUE(sim.marble().position.allFinite()) << c.what;
      ASSERT_EQ(sim.marble().phase, MarblePhase::Free) << c.what;
      std::vector<Contact> contacts;
      findContacts(sim.maze(), sim.gridFrame(), sim.marble().position, c.radius, 0, &contacts);
      for (const Contact& k : contacts) deepest = std::max(deepest, k.depth);
    }
    EXPECT_LE(deepest, 0.01 * c.radius) << c.what;
  }
}

TEST(Extremes, AThousandByAThousandCellMazeAndATwentyCubedStackOfTiles) {
  // 2001 x 2001 slots: a marble rolls across a corner of it; 20 x 20 x 20 tiles: a marble falls
  // through a lattice of floors with gaps, from the top to the bottom.
  {
    Maze big(AxisSlots(0.005, 0.0221, 2001), AxisSlots(0.005, 0.02325, 2001),
             AxisSlots(0.005, 0.012, 2));
    for (int j = 0; j < 2001; ++j)
      for (int i = 0; i < 2001; ++i) big.setSolid({i, j, 0}, true);
    big.setStart({1999, 1999});
    Params p;
    p.start_velocity = Vec3(-0.5, -0.3, 0);
    Simulation sim({big, p});
    for (int i = 0; i < 2000; ++i) sim.step();
    EXPECT_TRUE(sim.marble().position.allFinite());
    EXPECT_EQ(sim.marble().phase, MarblePhase::Free);
    EXPECT_LT(penetration(sim), 0.01 * kRadius);
  }
  {
    Maze stack(AxisSlots::uniform(0.02, 20), AxisSlots::uniform(0.02, 20),
               AxisSlots::uniform(0.02, 20));
    for (int k = 0; k < 20; k += 4)
      for (int j = 0; j < 20; ++j)
        for (int i = 0; i < 20; ++i)
          if (k == 0 || (i + j + k) % 5 != 0) stack.setSolid({i, j, k}, true);  // gaps above
    stack.setStart({10, 10});
    Params p = placed(Params(), {0.001, 0.001, 0.35});  // near the top of the stack
    p.restitution = 0.7;
    Simulation sim({stack, p});
    double deepest = 0;
    for (int i = 0; i < 5000; ++i) {
      sim.step();
      ASSERT_TRUE(sim.marble().position.allFinite());
      deepest = std::max(deepest, penetration(sim));
    }
    EXPECT_LE(deepest, 0.01 * kRadius);
  }
}

TEST(Extremes, AMarbleOnAnEdgeAVertexASeamOrWedgedInACornerRests) {
  // A floor of 1 cm tiles with a 1 cm step (a wall) along x = 0: the marble exactly over a floor
  // seam, over a vertex where four floor tiles meet, on top of the wall's edge (half over it),
  // and wedged in the corner between the wall, a cross wall and the floor under a tilt that
  // presses it in; at 1 ms and at 50 ms. Each moves less than a micrometre in 10 s.
  Maze maze(AxisSlots::uniform(0.01, 20), AxisSlots::uniform(0.01, 20),
            AxisSlots::uniform(0.01, 3));
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 20; ++i) {
      maze.setSolid({i, j, 0}, true);
      if (i == 10 || j == 5) maze.setSolid({i, j, 1}, true);  // walls: x in [0, 0.01], y = -0.05
    }
  maze.setStart({15, 15});
  struct Case {
    Vec3 at;
    double roll, pitch;
    const char* what;
  };
  const double top = kRadius, wall_top = 0.01 + kRadius;
  const Case cases[] = {{{0.055, 0.03, top}, 0, 0, "over a seam"},
                        {{0.05, 0.04, top}, 0, 0, "over a vertex of four tiles"},
                        {{0.0, 0.03, wall_top}, 0, 0, "on the wall's top, over its edge"},
                        {{0.01 + kRadius, -0.04 + kRadius, top}, 0.05, 0.05, "wedged in a corner"}};
  for (IntegratorKind integrator : kAll)
    for (double step : {1e-3, 0.05})
      for (const Case& c : cases) {
        Params p = placed(with(integrator, Model::Rolling, step), c.at);
        p.initial_roll = c.roll;     // positive roll lowers -y, positive pitch lowers +x: into the
        p.initial_pitch = -c.pitch;  // corner at the wall's +x face and the cross wall's +y face
        Simulation sim({maze, p});
        for (int i = 0; i < static_cast<int>(2.0 / step); ++i) sim.step();  // settle
        const Vec3 settled = sim.marbleInBoard();
        for (int i = 0; i < static_cast<int>(10.0 / step); ++i) sim.step();
        EXPECT_LT((sim.marbleInBoard() - settled).norm(), 1e-6) << name(p) << " " << c.what;
      }
}

/// The message of the ParamError that making a simulation of the scene throws, or "".
std::string refusal(const Scene& scene) {
  try {
    Simulation sim(scene);
  } catch (const ParamError& e) {
    return e.what();
  }
  return "";
}

TEST(Extremes, AMarbleThatCannotStartWhereItIsPutIsRefusedNamingTheKey) {
  Scene scene = loadScene("classic");
  // Inside the outer wall at the far-left corner (board frame: the grid less the pivot).
  const Vec3 wall = Vec3(scene.maze.axis(0).centre(0), scene.maze.axis(1).centre(3),
                         scene.maze.floorTop() + 0.006) -
                    scene.maze.pivot();
  Scene in_wall = scene;
  setParam(
      in_wall.params, "start_position",
      std::to_string(wall.x()) + "," + std::to_string(wall.y()) + "," + std::to_string(wall.z()));
  EXPECT_NE(refusal(in_wall).find(
                "start_position: a marble of radius 0.006 m cannot start there: inside tile (0,"),
            std::string::npos)
      << refusal(in_wall);
  Scene off_board = scene;
  setParam(off_board.params, "start_position", "1,0,0.006");
  EXPECT_NE(refusal(off_board).find("start_position"), std::string::npos) << refusal(off_board);
  // Under the board it was taken, and was off the board at once; a million metres above it,
  // it fell for minutes, drifting 1e290 m at 1e300.
  for (const std::pair<const char*, const char*>& bad :
       {std::pair{"0.0136,0.0706,-0.05", "below the board (its top under the floor's)"},
        {"0.0136,0.0706,1e6", "more than 100 m above the board"}}) {
    Scene where = scene;
    setParam(where.params, "start_position", bad.first);
    EXPECT_EQ(
        refusal(where),
        std::string("start_position: a marble of radius 0.006 m cannot start there: ") + bad.second)
        << bad.first;
  }
  Scene high = scene;  // a drop from 50 m is a drop
  setParam(high.params, "start_position", "0.0136,0.0706,50");
  EXPECT_EQ(refusal(high), "");
  Scene wide = scene;  // 3 cm across in a cell of 2.2 cm between walls
  setParam(wide.params, "marble_radius", "0.015");
  EXPECT_NE(refusal(wide).find("marble_radius: a marble of radius 0.015 m does not fit the start "
                               "cell"),
            std::string::npos)
      << refusal(wide);
  // The control: the default marble at the start cell, and one placed by hand on the floor.
  EXPECT_EQ(refusal(scene), "");
  Scene placed_well = scene;  // by hand where the start cell puts it
  placed_well.params.has_start_position = true;
  placed_well.params.start_position = Simulation(scene).startInBoard();
  EXPECT_EQ(refusal(placed_well), "");
}

TEST(Extremes, AMarbleWhoseStateIsNotFiniteIsTakenOffTheBoardNotSpreadNaN) {
  // The finish rules' last guard: placed by hand with a velocity that is not a number (nothing
  // the node or the runner lets through, which refuse it), the marble is taken off the board
  // after one step and held, finite, at the pivot, with an off_board event.
  for (const double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    Simulation sim(loadScene("classic"));
    sim.placeMarble(sim.startInBoard(), Vec3(bad, 0, 0));
    sim.step();
    EXPECT_EQ(sim.marble().phase, MarblePhase::OffBoard) << bad;
    EXPECT_TRUE(sim.marble().position.allFinite()) << bad;
    EXPECT_TRUE(sim.marble().velocity.allFinite()) << bad;
    ASSERT_EQ(sim.events().size(), 1u) << bad;
    EXPECT_EQ(sim.events()[0].kind, EventKind::OffBoard);
    for (int k = 0; k < 100; ++k) sim.step();  // and it stays so
    EXPECT_TRUE(sim.marble().position.allFinite() && sim.energy() == sim.energy()) << bad;
  }
}

TEST(Extremes, SettingsThatCannotBeSimulatedAreRefusedNamingTheKey) {
  Params p;
  p.start_velocity = Vec3(1e158, 0, 0);
  try {
    validate(p);
    FAIL() << "a velocity the sweep cannot resolve was accepted";
  } catch (const ParamError& e) {
    EXPECT_NE(std::string(e.what()).find("start_velocity"), std::string::npos) << e.what();
  }
  EXPECT_THROW(setParam(p, "step", "0"), ParamError);
  EXPECT_THROW(setParam(p, "marble_radius", "-1"), ParamError);
  EXPECT_THROW(setParam(p, "restitution", "nan"), ParamError);
  try {
    parseScene("grid:\n  x: [1e308, 1e308]\n  y: 0.01\n  z: 0.01\nlayout: |\n  S G\n", "huge.yaml");
    FAIL() << "slots of 1e308 m were accepted";
  } catch (const MazeFileError& e) {
    EXPECT_NE(std::string(e.what()).find("huge.yaml:2:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace marble_maze
