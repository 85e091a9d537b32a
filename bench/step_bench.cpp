// The cost of one simulation step, against the size of the maze and the physics switched on.
// Every figure is also printed as a ratio to the first case of its group, measured in the same
// run, so that the machine's speed cancels out.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "marble_maze/simulation.h"

namespace mm = marble_maze;

namespace {

/// An N x N cell maze of the classic game's proportions: outer walls, inner walls from a hash
/// of each wall's position relative to the centre, and a closed 4 x 4 cell room in the middle
/// where the marble runs. The room and its surroundings are the same in every size, so the
/// marble's path is too: only the size of the maze differs between the cases.
mm::Scene generatedScene(int cells) {
  const int n = 2 * cells + 1;
  const mm::AxisSlots x(0.005, 0.0221, n), y(0.005, 0.02325, n), z(0.005, 0.012, 2);
  mm::Maze maze(x, y, z);
  const int c = cells / 2 * 2 + 1;  // an odd (cell) slot near the centre
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      maze.setSolid({i, j, 0}, true);
      const bool post = i % 2 == 0 && j % 2 == 0;
      const bool wall_slot = (i % 2 == 0) != (j % 2 == 0);
      const bool outer = i == 0 || j == 0 || i == n - 1 || j == n - 1;
      const unsigned hash =
          static_cast<unsigned>((i - c) * 73856093) ^ static_cast<unsigned>((j - c) * 19349663);
      const bool room_wall = (std::abs(i - c) == 5 && std::abs(j - c) <= 5) ||
                             (std::abs(j - c) == 5 && std::abs(i - c) <= 5);
      const bool inside_room = std::abs(i - c) < 5 && std::abs(j - c) < 5;
      const bool inner_wall = wall_slot && !inside_room && hash % 3 == 0;
      if (post || outer || room_wall || inner_wall) maze.setSolid({i, j, 1}, true);
    }
  maze.setStart({c, c});
  maze.setName(std::to_string(cells) + "x" + std::to_string(cells));
  return {maze, mm::Params()};
}

const mm::Scene& sceneOfSize(int cells) {
  static std::map<int, mm::Scene> scenes;
  auto it = scenes.find(cells);
  if (it == scenes.end()) it = scenes.emplace(cells, generatedScene(cells)).first;
  return it->second;
}

/// Steps the simulation under a circling tilt (one turn in about 3 s), which keeps the marble
/// rolling into walls. The tilts are worked out beforehand so that only the step is timed.
void runSteps(benchmark::State& state, mm::Simulation* sim) {
  std::vector<std::pair<double, double>> tilts(3142);
  for (std::size_t i = 0; i < tilts.size(); ++i) {
    const double t = static_cast<double>(i) * sim->params().step;
    tilts[i] = {0.1 * std::sin(2.0 * t), 0.1 * std::cos(2.0 * t)};
  }
  std::size_t n = 0;
  for (auto _ : state) {
    const auto& [roll, pitch] = tilts[n++ % tilts.size()];
    sim->setTargetTilt(roll, pitch);
    sim->step();
    if (sim->marble().phase != mm::MarblePhase::Free) sim->reset();
  }
  state.counters["substeps"] = sim->params().substeps;
}

void BM_StepByMazeSize(benchmark::State& state) {
  mm::Simulation sim(sceneOfSize(static_cast<int>(state.range(0))));
  runSteps(state, &sim);
}
BENCHMARK(BM_StepByMazeSize)->ArgName("cells")->Arg(10)->Arg(100)->Arg(1000);

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
BENCHMARK(BM_StepByPhysics)->ArgName("physics")->DenseRange(0, 2);

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
BENCHMARK(BM_StepByIntegrator)->ArgNames({"integrator", "drag"})->ArgsProduct({{0, 1, 2}, {0, 1}});

void BM_StepBySubsteps(benchmark::State& state) {
  mm::Scene scene = sceneOfSize(10);
  scene.params.substeps = static_cast<int>(state.range(0));
  mm::Simulation sim(scene);
  runSteps(state, &sim);
}
BENCHMARK(BM_StepBySubsteps)->ArgName("substeps")->Arg(1)->Arg(4)->Arg(16);

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
    std::printf("\n%-40s %-26s %12s %8s\n", "case", "", "ns/step", "ratio");
    std::map<std::string, double> baseline;
    for (const Row& row : rows_) {
      const double base = baseline.emplace(row.group, row.ns).first->second;
      std::printf("%-40s %-26s %12.1f %8.2f\n", row.name.c_str(), row.label.c_str(), row.ns,
                  row.ns / base);
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
