// The cost of one simulation step, against the size of the maze and the physics switched on.
// Every figure is also printed as a ratio to the first case of its group, measured in the same
// run, so that the machine's speed cancels out.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "bench_mazes.h"
#include "marble_maze/agent_env.h"
#include "marble_maze/csv.h"
#include "marble_maze/exact_text.h"
#include "marble_maze/sensors.h"
#include "marble_maze/simulation.h"

namespace mm = marble_maze;

namespace marble_maze {
namespace bench {

// The cases' scenes and how often they start over.
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

/// The generated mazes' sizes, in cells a side, from 10 to 1000 (295 to 500 among them, where the
/// rounding of grid coordinates would grow with the maze if it were taken about its corner).
inline void mazeSizes(benchmark::internal::Benchmark* b) {
  b->ArgName("cells");
  for (int cells : {10, 100, 200, 295, 299, 300, 400, 500, 1000}) b->Arg(cells);
}

/// Steps the simulation under the circling tilt, and starts it over when it finishes or every
/// `restart_every` steps (0: never). The tilts are worked out beforehand so that only the step
/// is timed (and, with `rows`, a trajectory row of the runner's CSV after each step). Returns
/// the steps taken.
inline std::size_t stepUnderCirclingTilt(benchmark::State& state, Simulation* sim,
                                         std::size_t restart_every = 0,
                                         std::string* rows = nullptr) {
  const std::vector<std::pair<double, double>> tilts = circlingTilts(sim->params().step);
  std::size_t n = 0;
  for (auto _ : state) {
    const auto& [roll, pitch] = tilts[n++ % tilts.size()];
    sim->setTargetTilt(roll, pitch);
    sim->step();
    if (rows) {
      appendTrajectoryRow(rows, *sim);
      if (rows->size() > 65536) rows->clear();  // (as a file's buffer is written out)
    }
    if (sim->marble().phase != MarblePhase::Free || (restart_every && n % restart_every == 0))
      sim->reset();
  }
  return n;
}

}  // namespace bench
}  // namespace marble_maze

namespace {

/// A generated maze of `cells` x `cells` (negative: an open floor of that size), built once.
const mm::Scene& sceneOfSize(int cells) {
  static std::map<int, mm::Scene> scenes;
  auto it = scenes.find(cells);
  if (it == scenes.end())
    it = scenes
             .emplace(cells,
                      mm::Scene{mm::bench::generatedMaze(std::abs(cells), cells > 0), mm::Params()})
             .first;
  return it->second;
}

/// The timed loop, and what the steps cost in counts: substeps, sweeps, gathers, tiles swept,
/// and the pair solver's Newton steps a solve.
void runSteps(benchmark::State& state, mm::Simulation* sim, std::size_t restart_every = 0,
              std::string* rows = nullptr) {
  const mm::StepCounts before = sim->counts();
  const std::size_t n = mm::bench::stepUnderCirclingTilt(state, sim, restart_every, rows);
  const mm::StepCounts after = sim->counts();
  const double steps = static_cast<double>(std::max<std::size_t>(n, 1));
  state.counters["substeps"] = static_cast<double>(after.substeps - before.substeps) / steps;
  state.counters["sweeps/step"] = static_cast<double>(after.sweeps - before.sweeps) / steps;
  state.counters["clear/step"] =
      static_cast<double>(after.sweeps_clear - before.sweeps_clear) / steps;
  state.counters["gathers/step"] = static_cast<double>(after.gathers - before.gathers) / steps;
  state.counters["tiles/step"] =
      static_cast<double>(after.tiles_swept - before.tiles_swept) / steps;
  state.counters["newton/pair"] =
      static_cast<double>(after.pairs.newton_steps - before.pairs.newton_steps) /
      static_cast<double>(std::max<std::uint64_t>(after.pairs.solves - before.pairs.solves, 1));
}

/// With MARBLE_MAZE_BENCH_STEPS set (make instructions sets it), a case runs exactly that many
/// steps, once, rather than as many as fit a time: the same steps on any machine, so that a
/// count of their instructions is the same from run to run.
void fixedSteps(benchmark::internal::Benchmark* b) {
  const char* text = std::getenv("MARBLE_MAZE_BENCH_STEPS");
  if (!text) return;
  char* end = nullptr;
  const long long steps = std::strtoll(text, &end, 10);
  if (end == text || *end != '\0' || steps <= 0) {
    std::fprintf(stderr, "MARBLE_MAZE_BENCH_STEPS: '%s' is not a positive whole number\n", text);
    std::exit(2);
  }
  b->Iterations(steps);
}

/// The baseline: the step's fixed part. The marble falls from 1 m above the tilting board, far
/// from every tile, for 0.4 s at a time.
void BM_FreeFlight(benchmark::State& state) {
  mm::Simulation sim(mm::bench::inFreeFlight(sceneOfSize(mm::bench::kFreeFlightCells)));
  runSteps(state, &sim, mm::bench::kFreeFlightRestart);
}
BENCHMARK(BM_FreeFlight)->Apply(fixedSteps);

/// Rolling on an open floor of 60 x 60 cells inside the outer walls, started over every second:
/// under the circling tilt it never goes faster than 0.7 m/s, so it never reaches the walls 0.8 m
/// away.
void BM_OpenFloor(benchmark::State& state) {
  mm::Simulation sim(sceneOfSize(-mm::bench::kOpenFloorCells));
  runSteps(state, &sim, mm::bench::kOpenFloorRestart);
}
BENCHMARK(BM_OpenFloor)->Apply(fixedSteps);

/// The generated mazes: the cost must not grow with their size, nor jump at any one size.
void BM_StepByMazeSize(benchmark::State& state) {
  mm::Simulation sim(sceneOfSize(static_cast<int>(state.range(0))));
  runSteps(state, &sim);
}
BENCHMARK(BM_StepByMazeSize)->Apply(fixedSteps)->Apply(mm::bench::mazeSizes);

void BM_StepByPhysics(benchmark::State& state) {
  mm::Scene scene = sceneOfSize(10);
  const char* names[] = {"smooth", "rolling", "rolling+resistance+drag"};
  const int which = static_cast<int>(state.range(0));
  scene.params.model = which == 0 ? mm::Model::Smooth : mm::Model::Rolling;
  if (which == 2) {
    scene.params.rolling_resistance = 0.002;
    scene.params.drag_coefficient = 0.47;
  }
  state.SetLabel(names[which]);
  mm::Simulation sim(scene);
  runSteps(state, &sim);
}
BENCHMARK(BM_StepByPhysics)->Apply(fixedSteps)->ArgName("physics")->DenseRange(0, 2);

/// A marble rolling under the circling tilt in the 10 x 10 maze, then one at rest on the level
/// board there: asleep (Simulation::step), it costs next to nothing until something moves it.
void BM_RestingMarble(benchmark::State& state) {
  mm::Simulation sim(sceneOfSize(10));
  state.SetLabel(state.range(0) ? "at rest, level board" : "rolling");
  if (!state.range(0)) {
    runSteps(state, &sim);
    return;
  }
  for (auto _ : state) sim.step();
  state.counters["asleep"] = sim.resting();
}
BENCHMARK(BM_RestingMarble)->Apply(fixedSteps)->ArgName("resting")->Arg(0)->Arg(1);

/// Each integrator in the 10 x 10 maze, rolling, without and with air drag: RK4 asks the contacts
/// four times a step only when a force changes over the step (drag); otherwise its extra cost is
/// the board's frame it integrates in on a face.
void BM_StepByIntegrator(benchmark::State& state) {
  mm::Scene scene = sceneOfSize(10);
  const mm::IntegratorKind kinds[] = {mm::IntegratorKind::SemiImplicitEuler,
                                      mm::IntegratorKind::VelocityVerlet,
                                      mm::IntegratorKind::RungeKutta4};
  scene.params.integrator = kinds[state.range(0)];
  if (state.range(1)) scene.params.drag_coefficient = 0.47;
  state.SetLabel(mm::getParam(scene.params, "integrator") + (state.range(1) ? "+drag" : ""));
  mm::Simulation sim(scene);
  runSteps(state, &sim);
}
BENCHMARK(BM_StepByIntegrator)
    ->Apply(fixedSteps)
    ->ArgNames({"integrator", "drag"})
    ->ArgsProduct({{0, 1, 2}, {0, 1}});

void BM_StepBySubsteps(benchmark::State& state) {
  mm::Scene scene = sceneOfSize(10);
  scene.params.substeps = static_cast<int>(state.range(0));
  mm::Simulation sim(scene);
  runSteps(state, &sim);
}
BENCHMARK(BM_StepBySubsteps)->Apply(fixedSteps)->ArgName("substeps")->Arg(1)->Arg(4)->Arg(16);

/// simulate --out at every step: a step in the 10 x 10 maze, then the same with a trajectory row
/// of the CSV after it. The second's ratio in its group, less one, is a row's cost in steps.
void BM_StepWithCsvRow(benchmark::State& state) {
  mm::Simulation sim(sceneOfSize(10));
  std::string rows;
  runSteps(state, &sim, 0, state.range(0) ? &rows : nullptr);
}
BENCHMARK(BM_StepWithCsvRow)->Apply(fixedSteps)->ArgName("row")->Arg(0)->Arg(1);

/// One number of that row in its shortest exact form, over numbers of a simulation's scales
/// (1e-4 to 10, either sign): std::to_chars's shortest scientific form, the standard library's
/// one call, then writeExact, the CSV's form (Dragonbox's digits laid out as %g lays them out).
/// The second's ratio in its group is writeExact's cost against std::to_chars's.
void BM_NumberText(benchmark::State& state) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::vector<double> numbers(4096);
  for (double& v : numbers) v = unit(random) * std::pow(10.0, static_cast<int>(random() % 6) - 4);
  const bool exact = state.range(0);
  state.SetLabel(exact ? "writeExact" : "std::to_chars");
  char text[mm::kExactTextSize];
  std::size_t k = 0;
  for (auto _ : state) {
    const double v = numbers[k++ % numbers.size()];
    char* end = exact
                    ? mm::writeExact(text, v)
                    : std::to_chars(text, text + sizeof text, v, std::chars_format::scientific).ptr;
    benchmark::DoNotOptimize(end);
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_NumberText)->Apply(fixedSteps)->ArgName("exact")->Arg(0)->Arg(1);

/// Random actions in [-1, 1] for `count` environments, each from a stream of its own: the
/// environment numbered `first + i` draws the same actions however the environments are batched,
/// so that every case below plays the same games.
class RandomActions {
 public:
  RandomActions(int first, int count) {
    for (int i = 0; i < count; ++i) streams_.push_back(mm::splitMix64(first + i));
  }
  /// The next action of each environment: count x kActionSize values.
  void draw(double* out) {
    for (std::uint64_t& stream : streams_)
      for (int k = 0; k < mm::AgentEnv::kActionSize; ++k) *out++ = 2 * mm::uniformDraw(&stream) - 1;
  }

 private:
  std::vector<std::uint64_t> streams_;
};

/// Learning agents: a control step (1/55 s of the classic maze at the `fast` preset) under random
/// actions, per environment. envs:0 is the in-process loop an author writes by hand on one
/// Session (a command, a period's steps, nothing observed); the others are VectorAgentEnv's
/// step of that many environments on that many threads, observations and rewards included.
/// The last runs two benchmark threads at once, each a VectorAgentEnv(32) of its own on one
/// thread, the first and the second half of the 64: the two cores' rate with nothing shared and
/// no call waiting for the other core, the most a VectorAgentEnv(64) on two threads could reach
/// on the machine as it is in this run. The ratio in the group is a control step's cost against
/// the hand-written loop's.
void BM_AgentControlStep(benchmark::State& state) {
  const int envs = static_cast<int>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  mm::AgentEnvOptions options;
  RandomActions random(state.thread_index() * envs, std::max(envs, 1));
  if (envs == 0) {
    const mm::Scene scene = mm::agentScene(options);
    mm::Session session(scene);
    const auto steps = static_cast<std::uint64_t>(std::llround(1 / 55.0 / scene.params.step));
    double a[mm::AgentEnv::kActionSize];
    for (auto _ : state) {
      random.draw(a);
      session.command({session.steps(), mm::TiltCommand::Kind::Angles,
                       a[0] * scene.params.tilt_limit, a[1] * scene.params.tilt_limit});
      session.run(steps);
      if (session.simulation().marble().phase != mm::MarblePhase::Free) session.reset();
    }
    state.SetItemsProcessed(state.iterations());
    return;
  }
  if (state.threads() > 1) state.SetLabel("apart: the cores' most");
  mm::VectorAgentEnv vector(envs, options, threads);
  const std::size_t n = static_cast<std::size_t>(envs);
  std::vector<float> obs(n * mm::AgentEnv::kObservationSize), final_obs(obs.size());
  std::vector<double> rewards(n), batch(n * mm::AgentEnv::kActionSize);
  std::vector<std::uint8_t> terminated(n), truncated(n);
  vector.reset(obs.data());
  for (auto _ : state) {
    random.draw(batch.data());
    vector.step(batch.data(), obs.data(), rewards.data(), terminated.data(), truncated.data(),
                final_obs.data());
  }
  state.SetItemsProcessed(state.iterations() * envs);
}
BENCHMARK(BM_AgentControlStep)
    ->ArgNames({"envs", "threads"})
    ->Args({0, 1})
    ->Args({1, 1})
    ->Args({8, 1})
    ->Args({64, 1})
    ->Args({64, 2})
    ->UseRealTime();
BENCHMARK(BM_AgentControlStep)
    ->ArgNames({"envs", "threads"})
    ->Args({32, 1})
    ->Threads(2)
    ->UseRealTime();

/// Prints the usual table, then each case as a ratio to the first case of its group.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      if (run.run_type != Run::RT_Iteration || run.error_occurred) continue;
      const std::string name = run.benchmark_name();
      // (A case that counts items, a control step of each environment, is timed per item.)
      const auto items = run.counters.find("items_per_second");
      const double ns =
          items != run.counters.end() && items->second.value > 0
              ? 1e9 / items->second.value
              : run.GetAdjustedRealTime() * 1e9 / benchmark::GetTimeUnitMultiplier(run.time_unit);
      rows_.push_back({name.substr(0, name.find('/')), name, run.report_label, ns});
    }
  }
  void Finalize() override {
    ConsoleReporter::Finalize();
    // The free flight is every case's baseline, and the first case of a group its group's.
    double flight = 0;
    for (const Row& row : rows_)
      if (row.group == "BM_FreeFlight") flight = row.ns;
    std::printf("\n%-40s %-26s %10s %10s %12s\n", "case", "", "ns/step", "in group",
                "/ free flight");
    std::map<std::string, double> baseline;
    for (const Row& row : rows_) {
      const double base = baseline.emplace(row.group, row.ns).first->second;
      std::printf("%-40s %-26s %10.1f %10.2f %12.2f\n", row.name.c_str(), row.label.c_str(), row.ns,
                  row.ns / base, flight > 0 ? row.ns / flight : 0.0);
    }
  }

 private:
  struct Row {
    std::string group, name, label;
    double ns;
  };

  std::vector<Row> rows_;
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
