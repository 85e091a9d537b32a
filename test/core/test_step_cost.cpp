// The step's cost counted, not timed: the solid tiles the swept test looks at per step stay
// within a bound at every maze size, so that no size has a cliff, and the pair solver's Newton
// steps within one a solve (make bench times the same scenes).
#include <gtest/gtest.h>

#include <cmath>

#include "bench_mazes.h"
#include "marble_maze/simulation.h"
#include "scenes.h"

namespace marble_maze {
namespace {

/// Tiles swept per step over `steps` steps in a generated maze of `cells` x `cells`: the marble
/// at rest on a level board, or rolling under the circling tilt of make bench.
double tilesPerStep(int cells, bool circling, int steps = 2000) {
  Simulation sim(Scene{bench::generatedMaze(cells), Params()});
  for (int n = 0; n < steps; ++n) {
    const double t = n * sim.params().step;
    if (circling) sim.setTargetTilt(0.1 * std::sin(2.0 * t), 0.1 * std::cos(2.0 * t));
    sim.step();
  }
  return static_cast<double>(sim.counts().tiles_swept) / steps;
}

TEST(StepCost, TilesSweptPerStepAreBoundedAtEveryMazeSize) {
  // The same room in every size (see generatedMaze): the walk's cost may not grow with the maze
  // nor jump at one size. A marble at rest is never swept; a rolling one looks at a tile every
  // dozen steps or so (0.07 a step today: mostly when it meets a wall), within 1.15 times what
  // the smallest maze costs.
  const double smallest = tilesPerStep(10, true);
  EXPECT_GT(smallest, 0.02);  // the count counts
  EXPECT_LT(smallest, 4.0);
  for (int cells : {10, 100, 200, 295, 299, 300, 400, 500, 1000}) {
    EXPECT_EQ(tilesPerStep(cells, false), 0.0) << cells << " x " << cells << ", at rest";
    EXPECT_LE(tilesPerStep(cells, true), 1.15 * smallest) << cells << " x " << cells;
  }
}

TEST(StepCost, ThePairSolverTakesOneNewtonStepForAMarbleRollingAlongAWall) {
  // Under make bench's circling tilt the marble rolls along the room's walls, a floor and a wall
  // at once, one sticking and the other slipping, in a third of its steps. The pair solver
  // starts Newton's method from the root of its equation without the slip across the two
  // surfaces, which is the root when they move as one board, and takes one step a solve (here
  // 2.6 in make bench's maze of 100 cells).
  // A count: what make bench's newton/pair shows.
  Simulation sim(Scene{bench::generatedMaze(10), Params()});
  for (int n = 0; n < 4000; ++n) {
    const double t = n * sim.params().step;
    sim.setTargetTilt(0.1 * std::sin(2.0 * t), 0.1 * std::cos(2.0 * t));
    sim.step();
  }
  const PairSolveCounts pairs = sim.counts().pairs;
  EXPECT_GT(pairs.solves, 1000u);  // the count counts
  EXPECT_LE(static_cast<double>(pairs.newton_steps), 1.05 * static_cast<double>(pairs.solves));
  sim.setParams(sim.params());  // a new solver: the counts go on from where they were
  EXPECT_EQ(sim.counts().pairs.solves, pairs.solves);
  EXPECT_EQ(sim.counts().pairs.newton_steps, pairs.newton_steps);
}

TEST(StepCost, AMarbleRollingOnATurningFloorStaysOnIt) {
  // On an open floor, a marble starts 18 cm from the pivot and rolls for 10 s under a tilt of
  // 0.1 rad that circles either way round (0.2 rad/s) or wanders (a Lissajous figure), its speed
  // changing every step, in 1 ms steps and in the `fast` preset's 5 ms. It rolls at up to about
  // 1 m/s and meets the outer walls. The floor holds it: a sweep finds an impact (a second sweep
  // in its step) only as it lands and at the walls, 19 to 53 times a run. It used to leave the
  // floor wherever the surface under it dropped away faster than the lag a held contact is
  // allowed, and meet it again within the step: 134 to 908 times in the wandering runs and in
  // one of the circling ones, before the turn of the surface's normal under the marble was
  // counted in that lag.
  struct Tilt {
    double roll_rate, pitch_rate;  // of the sine and cosine, rad/s
  };
  for (const char* preset : {"realtime", "fast"})
    for (const Tilt tilt : {Tilt{2.0, 2.0}, Tilt{-2.0, -2.0}, Tilt{0.9, 0.7}, Tilt{0.9, 1.3}}) {
      Params p;
      setParam(p, "preset", preset);
      p.has_start_position = true;
      p.start_position = Vec3(0.15, 0.1, p.marble_radius);
      Simulation sim(Scene{bench::generatedMaze(60, false), p});
      while (sim.time() < 10.0) {
        const double t = sim.time();
        sim.setTargetTilt(0.1 * std::sin(tilt.roll_rate * t), 0.1 * std::cos(tilt.pitch_rate * t));
        sim.step();
      }
      ASSERT_EQ(sim.marble().phase, MarblePhase::Free);
      EXPECT_LE(sim.counts().sweeps - sim.counts().substeps, 80u)
          << preset << ", tilt rates " << tilt.roll_rate << ", " << tilt.pitch_rate;
    }
}

}  // namespace
}  // namespace marble_maze
