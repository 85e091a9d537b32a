// The scenes and the timed loop of the step's benchmarks, shared by make bench (step_bench.cpp)
// and make speedup (step_cost.cpp). They ask of the core only what its interface had at the
// first commit, so that make speedup can time an earlier core and this one on the same cases.
#pragma once

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "generated_maze.h"
#include "marble_maze/maze_file.h"
#include "marble_maze/simulation.h"

namespace marble_maze {
namespace bench {

// The cases' scenes and how often they start over, as make bench and make speedup both run them.
constexpr int kFreeFlightCells = 10;             ///< the maze far under the falling marble
constexpr std::size_t kFreeFlightRestart = 400;  ///< steps: 0.4 s of flight at a time
constexpr int kOpenFloorCells = 60;              ///< an open floor of 60 x 60 cells, walled round
constexpr std::size_t kOpenFloorRestart = 1000;  ///< steps: a second, too short to reach a wall

/// The tilt programme, a step of `step` seconds at a time: a circling tilt of 0.1 rad, one turn
/// in about 3 s, which keeps the marble rolling into walls; it repeats after 3142 steps.
inline std::vector<std::pair<double, double>> circlingTilts(double step) {
  std::vector<std::pair<double, double>> tilts(3142);
  for (std::size_t i = 0; i < tilts.size(); ++i) {
    const double t = static_cast<double>(i) * step;
    tilts[i] = {0.1 * std::sin(2.0 * t), 0.1 * std::cos(2.0 * t)};
  }
  return tilts;
}

/// The baseline, the step's fixed part: the scene's marble starts 1 m above the board's pivot,
/// far from every tile.
inline Scene inFreeFlight(Scene scene) {
  scene.params.has_start_position = true;
  scene.params.start_position = Vec3(0, 0, 1.0);
  return scene;
}

/// The generated mazes' sizes, in cells a side: issue 11's, where a cliff once showed (295, 299,
/// 300, 400, 500), among others from 10 to 1000.
inline void mazeSizes(benchmark::internal::Benchmark* b) {
  b->ArgName("cells");
  for (int cells : {10, 100, 200, 295, 299, 300, 400, 500, 1000}) b->Arg(cells);
}

/// Steps the simulation under the circling tilt, and starts it over when it finishes or every
/// `restart_every` steps (0: never). The tilts are worked out beforehand so that only the step
/// is timed. Returns the steps taken.
inline std::size_t stepUnderCirclingTilt(benchmark::State& state, Simulation* sim,
                                         std::size_t restart_every = 0) {
  const std::vector<std::pair<double, double>> tilts = circlingTilts(sim->params().step);
  std::size_t n = 0;
  for (auto _ : state) {
    const auto& [roll, pitch] = tilts[n++ % tilts.size()];
    sim->setTargetTilt(roll, pitch);
    sim->step();
    if (sim->marble().phase != MarblePhase::Free || (restart_every && n % restart_every == 0))
      sim->reset();
  }
  return n;
}

}  // namespace bench
}  // namespace marble_maze
