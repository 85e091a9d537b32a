// The cost of one simulation step, against the size of the maze and the physics switched on.
// Every figure is also printed as a ratio to the first case of its group, measured in the same
// run, so that the machine's speed cancels out.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "marble_maze/simulation.h"
#include "step_loop.h"

namespace mm = marble_maze;

namespace {

/// A generated maze of `cells` x `cells` (negative: an open floor of that size), built once.
const mm::Scene& sceneOfSize(int cells) {
  static std::map<int, mm::Scene> scenes;
  auto it = scenes.find(cells);
  if (it == scenes.end())
    it = scenes
             .emplace(cells,
                      mm::Scene{mm::test::generatedMaze(std::abs(cells), cells > 0), mm::Params()})
             .first;
  return it->second;
}

/// The timed loop (step_loop.h), and what the steps cost in counts: substeps, sweeps, gathers,
/// tiles swept, and the pair solver's Newton steps a solve.
void runSteps(benchmark::State& state, mm::Simulation* sim, std::size_t restart_every = 0) {
  const mm::StepCounts before = sim->counts();
  const std::size_t n = mm::bench::stepUnderCirclingTilt(state, sim, restart_every);
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

/// Each integrator in the 10 x 10 maze, rolling, without and with air drag: RK4 asks the contacts
/// four times a step only when a force changes over the step (drag); otherwise it costs what
/// velocity Verlet does.
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

/// Prints the usual table, then each case as a ratio to the first case of its group.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      if (run.run_type != Run::RT_Iteration || run.error_occurred) continue;
      const std::string name = run.benchmark_name();
      rows_.push_back(
          {name.substr(0, name.find('/')), name, run.report_label,
           run.GetAdjustedRealTime() * 1e9 / benchmark::GetTimeUnitMultiplier(run.time_unit)});
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
    printTargets();
  }

 private:
  struct Row {
    std::string group, name, label;
    double ns;
  };

  /// Issue 11's targets, for the cases of this run that they name: the most ns a step of a
  /// group's costliest case and, for the mazes, of their costliest size against the smallest.
  void printTargets() const {
    struct Target {
      const char* what;
      const char* group;
      double most_ns;
      double most_ratio;  // the costliest case against the group's first, the smallest (0: none)
    };
    const Target targets[] = {
        {"free flight", "BM_FreeFlight", 100, 0},
        {"rolling on an open floor", "BM_OpenFloor", 100, 0},
        {"generated mazes, the costliest size", "BM_StepByMazeSize", 150, 1.15}};
    const auto line = [](const std::string& what, double value, double most) {
      char verdict[48] = "met";
      if (value > most) std::snprintf(verdict, sizeof verdict, "%.2f x the target", value / most);
      std::printf("%-67s %10.2f %10.2f  %s\n", what.c_str(), value, most, verdict);
    };
    bool header = false;
    for (const Target& target : targets) {
      double first = 0, costliest = 0;
      int cases = 0;
      for (const Row& row : rows_)
        if (row.group == target.group) {
          if (cases++ == 0) first = row.ns;
          costliest = std::max(costliest, row.ns);
        }
      if (costliest == 0) continue;  // not in this run
      if (!header)
        std::printf("\n%-67s %10s %10s  %s\n", "issue 11's targets", "this run", "target",
                    "verdict");
      header = true;
      line(std::string(target.what) + ", ns a step", costliest, target.most_ns);
      if (target.most_ratio > 0 && cases > 1)  // (one size alone says nothing of a cliff)
        line(std::string(target.what) + " / the smallest", costliest / first, target.most_ratio);
    }
  }

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
