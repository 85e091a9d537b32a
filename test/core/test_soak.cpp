// Long runs: a marble at rest, and a marble tilted at random in the classic maze with its holes
// and goal closed, for MARBLE_MAZE_SOAK_STEPS steps each (1,000,000 in make test; make soak runs
// 10,000,000): nothing drifts, nothing escapes, nothing becomes NaN.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <random>

#include "marble_maze/maze_file.h"
#include "marble_maze/simulation.h"
#include "scenes.h"

namespace marble_maze {
namespace {

constexpr double kRadius = 0.006;

long soakSteps() {
  const char* text = std::getenv("MARBLE_MAZE_SOAK_STEPS");
  return text ? std::atol(text) : 1000000;
}

TEST(Soak, AMarbleAtRestStaysPut) {
  Simulation sim(test::flatFloor(10, 10, 0.01, test::placed(Params(), {0.001, -0.002, kRadius})));
  const Vec3 start = sim.marble().position;
  const long steps = soakSteps();
  double fastest = 0;
  for (long i = 0; i < steps; ++i) {
    sim.step();
    fastest = std::max(fastest, sim.marble().velocity.norm());
  }
  const double drift = (sim.marble().position - start).norm();
  std::printf("at rest for %ld steps: drift %.3g m, fastest %.3g m/s\n", steps, drift, fastest);
  EXPECT_LT(drift, 1e-9);     // m
  EXPECT_LT(fastest, 1e-12);  // m/s
}

TEST(Soak, RandomTiltingInTheClassicMazeNeverEscapes) {
  // The classic maze with its holes filled and no goal: the marble plays for the whole run.
  const Maze maze = test::closedClassic();
  Simulation sim({maze, Params()});
  std::mt19937 random(7);  // the same targets every run
  const auto angle = [&] { return (random() % 2001 - 1000) * 1e-3 * 0.17; };
  const long steps = soakSteps();
  double deepest = 0, fastest = 0;
  long impacts = 0;
  for (long i = 0; i < steps; ++i) {
    if (i % 500 == 0) sim.setTargetTilt(angle(), angle());  // a new target every 0.5 s
    sim.step();
    impacts += static_cast<long>(sim.events().size());
    const Vec3 g = sim.marbleInBoard() + maze.pivot();
    ASSERT_TRUE(g.allFinite()) << "step " << i;
    ASSERT_EQ(sim.marble().phase, MarblePhase::Free) << "step " << i;
    ASSERT_TRUE(g.x() > 0 && g.y() > 0 && g.x() < maze.extent().x() && g.y() < maze.extent().y())
        << "step " << i;
    deepest = std::max(deepest, kRadius - (g.z() - maze.floorTop()));
    fastest = std::max(fastest, sim.marble().velocity.norm());
  }
  std::printf(
      "random tilting for %ld steps: %ld impacts, deepest below the floor's top %.3g m, "
      "fastest %.3g m/s\n",
      steps, impacts, deepest, fastest);
  EXPECT_LT(deepest, 0.01 * kRadius);  // never into the floor by 1% of the radius
  EXPECT_GT(impacts, steps / 10000);   // it did play
}

}  // namespace
}  // namespace marble_maze
