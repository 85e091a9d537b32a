// make speedup's benchmark: issue 11's cases (free flight, the open floor, the generated mazes)
// as make bench runs them, built against only the core's interface of the day the issue was
// filed, so that scripts/speedup.sh can build it against that core and this one and time both,
// in turns, on the same machine: a speed-up no machine's speed moves.
#include <benchmark/benchmark.h>

#include "marble_maze/simulation.h"
#include "step_loop.h"

namespace mm = marble_maze;

namespace {

void BM_FreeFlight(benchmark::State& state) {
  mm::Simulation sim(mm::bench::inFreeFlight(
      {mm::test::generatedMaze(mm::bench::kFreeFlightCells), mm::Params()}));
  mm::bench::stepUnderCirclingTilt(state, &sim, mm::bench::kFreeFlightRestart);
}
BENCHMARK(BM_FreeFlight);

void BM_OpenFloor(benchmark::State& state) {
  mm::Simulation sim({mm::test::generatedMaze(mm::bench::kOpenFloorCells, false), mm::Params()});
  mm::bench::stepUnderCirclingTilt(state, &sim, mm::bench::kOpenFloorRestart);
}
BENCHMARK(BM_OpenFloor);

void BM_StepByMazeSize(benchmark::State& state) {
  mm::Simulation sim({mm::test::generatedMaze(static_cast<int>(state.range(0))), mm::Params()});
  mm::bench::stepUnderCirclingTilt(state, &sim);
}
BENCHMARK(BM_StepByMazeSize)->Apply(mm::bench::mazeSizes);

}  // namespace

BENCHMARK_MAIN();
