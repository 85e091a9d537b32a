// The step's cost counted, not timed: the solid tiles the swept test looks at per step stay
// within a bound at every maze size, so that no size has a cliff (make bench times the same
// scenes).
#include <gtest/gtest.h>

#include <cmath>

#include "marble_maze/simulation.h"
#include "scenes.h"

namespace marble_maze {
namespace {

/// Tiles swept per step over `steps` steps in a generated maze of `cells` x `cells`: the marble
/// at rest on a level board, or rolling under the circling tilt of make bench.
double tilesPerStep(int cells, bool circling, int steps = 2000) {
  Simulation sim(Scene{test::generatedMaze(cells), Params()});
  for (int n = 0; n < steps; ++n) {
    const double t = n * sim.params().step;
    if (circling) sim.setTargetTilt(0.1 * std::sin(2.0 * t), 0.1 * std::cos(2.0 * t));
    sim.step();
  }
  return static_cast<double>(sim.counts().tiles_swept) / steps;
}

TEST(StepCost, TilesSweptPerStepAreBoundedAtEveryMazeSize) {
  // The same room in every size (see generatedMaze): the walk's cost may not grow with the maze
  // nor jump at one size. A marble at rest is never swept; a rolling one looks at a few tiles a
  // step (about 2.7 today), within 1.15 times what the smallest maze costs.
  const double smallest = tilesPerStep(10, true);
  EXPECT_GT(smallest, 0.5);  // the count counts
  EXPECT_LT(smallest, 4.0);
  for (int cells : {10, 100, 200, 295, 299, 300, 400, 500, 1000}) {
    EXPECT_EQ(tilesPerStep(cells, false), 0.0) << cells << " x " << cells << ", at rest";
    EXPECT_LE(tilesPerStep(cells, true), 1.15 * smallest) << cells << " x " << cells;
  }
}

}  // namespace
}  // namespace marble_maze
