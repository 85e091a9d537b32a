// simulate: the headless runner. Runs the physics core without ROS on a maze, under a constant
// tilt or a tilt program, and writes the trajectory as CSV and the events.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "marble_maze/csv.h"
#include "marble_maze/simulation.h"
#include "runner_options.h"
#include "runner_output.h"

namespace mm = marble_maze;
using mm::runner::Options;
using mm::runner::parseOptions;
using mm::runner::prepare;
using mm::runner::printHelp;
using mm::runner::Run;
using mm::runner::UsageError;

namespace {

using mm::runner::listFinishes;
using mm::runner::openOutput;
using mm::runner::summaryStream;
using mm::runner::writeEvents;
using mm::runner::writeRow;

int run(const Options& o) {
  if (!o.bag.empty())
    throw UsageError(
        "--bag: a recorded session is re-simulated by resimulate: rosrun marble_maze "
        "resimulate --bag " +
        o.bag + (o.check ? " --check" : ""));
  if (o.check) throw UsageError("--check: only with resimulate --bag");
  Run prepared = prepare(o);
  const mm::Scene& scene = prepared.scene;
  const mm::Simulation& sim = prepared.session->simulation();
  std::unique_ptr<std::ofstream> out_file, events_file;
  std::ostream* out = openOutput(o.out, &out_file);
  std::ostream* events = openOutput(o.events, &events_file);
  if (out) {
    *out << mm::kTrajectoryColumns;
    writeRow(*out, sim);
  }
  if (events) *events << mm::kEventColumns;
  // Whole steps: the duration's nearest, said when it is not one (a duration under half a step
  // would run none).
  const double step = scene.params.step;
  const auto steps = o.duration > 0 ? std::max<std::uint64_t>(1, std::llround(o.duration / step))
                                    : std::uint64_t{0};
  if (std::abs(static_cast<double>(steps) * step - o.duration) > 1e-9 * std::max(o.duration, step))
    std::cerr << "simulate: --duration " << mm::exactText(o.duration)
              << " s is not a whole number of steps of " << mm::exactText(step) << " s; runs "
              << steps << (steps == 1 ? " step" : " steps") << " ("
              << mm::exactText(static_cast<double>(steps) * step) << " s)\n";
  std::vector<mm::Event> all_events;
  for (std::uint64_t n = 1; n <= steps; ++n) {
    mm::runner::playStep(o, &prepared);
    const std::vector<mm::Event>& step_events = prepared.session->events();
    all_events.insert(all_events.end(), step_events.begin(), step_events.end());
    writeEvents(events, step_events);
    if (out && (n % o.every == 0 || n == steps)) writeRow(*out, sim);
  }
  if (!o.quiet) {
    std::ostream& s = summaryStream(o);
    const mm::Marble& m = sim.marble();
    const mm::Vec3 b = sim.marbleInBoard();
    s << "maze " << sim.maze().name() << ": " << sim.maze().size().x() << " x "
      << sim.maze().size().y() << " x " << sim.maze().size().z() << " tiles, model "
      << mm::getParam(scene.params, "model") << ", integrator "
      << mm::getParam(scene.params, "integrator") << ", step " << scene.params.step << " s x "
      << scene.params.substeps << "\n";
    const int collisions = listFinishes(s, all_events);
    s << "ran " << steps << " steps (" << sim.time() << " s): " << collisions
      << " collisions; marble " << mm::phaseName(m.phase) << " at board (" << b.x() << ", " << b.y()
      << ", " << b.z() << ") m, speed " << m.velocity.norm() << " m/s\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options options = parseOptions(std::vector<std::string>(argv + 1, argv + argc));
    if (options.help) {
      printHelp(std::cout);
      return 0;
    }
    return run(options);
  } catch (const UsageError& e) {
    std::cerr << "simulate: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "simulate: " << e.what() << "\n";
    return 1;
  }
}
