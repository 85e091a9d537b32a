// resimulate: a session recorded by record.launch re-simulated offline, from its first snapshot,
// with its inputs at their steps, without a ROS master; with --check compared with the recorded
// marble_state bit for bit, with --set under other physics. The ROS layer's half of the runner:
// simulate is the core's.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "../tools/runner_options.h"
#include "../tools/runner_output.h"
#include "marble_maze/csv.h"
#include "recording.h"

namespace mm = marble_maze;
using mm::runner::Options;
using mm::runner::UsageError;

namespace {

void printHelp(std::ostream& out) {
  out << R"(Usage: resimulate --bag FILE [OPTION]...
Re-simulates a session recorded by record.launch, from its first snapshot, with its inputs at
their steps, without a ROS master.

  --bag FILE           the recorded session (required)
  --check              compare with the bag's recorded marble_state, bit for bit; exit 1 at the
                       first difference, printing its stamp and size (not with --set: other
                       physics make other states)
  --set KEY=VALUE      re-run it under other physics (repeatable; keys as simulate --help lists)
  --out FILE           write the trajectory as CSV ('-' for standard output)
  --events FILE        write the events as CSV ('-' for standard output)
  --every N            write every Nth step to the trajectory; default 1
  --quiet              no summary on standard output
  --help, -h           this text

The bag brings the maze, the tilts and the length: --maze, --tilt, --tilt-csv, --duration,
--tilt-timeout and --auto-reset are refused. The CSVs' columns are simulate's.

Exit status: 0 done (and with --check, every state identical), 1 a difference or another
failure, 2 a wrong flag, value or bag.
)";
}

/// The marble and the tilt at an instant: what a recorded state shows (its position in the
/// world, as the node publishes it).
struct Shown {
  mm::Vec3 position;
  mm::Marble marble;
  double roll, pitch;
};

Shown shown(const mm::Simulation& sim) {
  return {sim.worldPosition(), sim.marble(), sim.board().roll(), sim.board().pitch()};
}

/// How a recorded state differs from what the simulation shows ("" when it is exactly it).
std::string differs(const marble_maze::MarbleState& recorded, const Shown& now) {
  const mm::Marble& m = now.marble;
  const auto vec = [](const auto& v) { return mm::Vec3(v.x, v.y, v.z); };
  const std::pair<const char*, double> gaps[] = {
      {"position", (vec(recorded.position) - now.position).norm()},
      {"velocity", (vec(recorded.velocity) - m.velocity).norm()},
      {"angular_velocity", (vec(recorded.angular_velocity) - m.angular_velocity).norm()},
      {"roll", std::abs(recorded.roll - now.roll)},
      {"pitch", std::abs(recorded.pitch - now.pitch)}};
  for (const auto& [field, gap] : gaps)
    if (gap != 0) {
      char text[128];
      std::snprintf(text, sizeof text, "%s differs by %.3g", field, gap);
      return text;
    }
  return "";
}

/// The recorded session again, and with --check the comparison.
int rerun(const Options& o) {
  marble_maze_ros::Recording recording;
  std::unique_ptr<marble_maze_ros::Replayer> replay;
  try {
    recording = marble_maze_ros::readRecording(o.bag);
    replay = std::make_unique<marble_maze_ros::Replayer>(recording, o.sets);
  } catch (const mm::MazeFileError& e) {
    throw UsageError(std::string("--bag: ") + e.what());
  } catch (const mm::ParamError& e) {  // the bag's own values, or those --sets gave over them
    throw mm::runner::physicsRefusal(o, e, "--bag: ");
  } catch (const std::runtime_error& e) {
    throw UsageError(std::string("--bag: ") + e.what());
  }
  std::unique_ptr<std::ofstream> out_file, events_file;
  std::ostream* out = mm::runner::openOutput(o.out, &out_file);
  std::ostream* events = mm::runner::openOutput(o.events, &events_file);
  const mm::Simulation& sim = replay->session().simulation();
  if (out) {
    *out << mm::kTrajectoryColumns;
    mm::runner::writeRow(*out, sim);
  }
  if (events) *events << mm::kEventColumns;
  const auto& states = recording.states;
  std::size_t next = 0, matched = 0, paused = 0, steps = 0;
  std::vector<mm::Event> all_events;
  while (next < states.size() && states[next].header.stamp < replay->stamp()) ++next;
  const ros::Time end = replay->end();
  for (;;) {
    // A state recorded at this step's stamp shows the simulation before or after the inputs
    // that came between the steps (a reset shown at once).
    const Shown before = shown(sim);
    try {
      replay->applyDue();
    } catch (const mm::ParamError& e) {  // a recorded load or reconfigure (under --set's values)
      throw UsageError(std::string(o.sets.empty() ? "--bag: " : "--set: ") + e.what());
    }
    const ros::Time stamp = replay->stamp();
    for (; next < states.size() && states[next].header.stamp <= stamp; ++next) {
      if (states[next].header.stamp < stamp) {  // published while paused: not a step's
        ++paused;
        continue;
      }
      ++matched;
      const std::string gap_before = differs(states[next], before);
      const std::string gap = differs(states[next], shown(sim));
      if (o.check && !gap_before.empty() && !gap.empty()) {
        // (The stamp as ros::Time prints it, exact to the nanosecond.)
        std::cerr << "resimulate: --check: the state stamped " << stamp << " s (simulated time "
                  << mm::exactText(sim.time()) << " s, step " << sim.steps() << "): " << gap
                  << "\n";
        return 1;
      }
    }
    if (stamp >= end) break;
    replay->step();
    mm::runner::writeEvents(events, replay->session().events());
    all_events.insert(all_events.end(), replay->session().events().begin(),
                      replay->session().events().end());
    ++steps;
    if (out && (steps % o.every == 0)) mm::runner::writeRow(*out, sim);
  }
  if (out && steps % o.every != 0)
    mm::runner::writeRow(*out, sim);  // the last step, as a run writes it
  if (o.check && matched == 0) {
    std::cerr << "resimulate: --check: " << o.bag
              << " holds no marble_state of the re-simulated steps: nothing to compare\n";
    return 1;
  }
  if (!o.quiet) {
    std::ostream& s = mm::runner::summaryStream(o);
    const int collisions = mm::runner::listFinishes(s, all_events);
    s << "re-simulated " << steps << " steps of " << o.bag << " from its first snapshot (step "
      << recording.snapshot.step << "): " << collisions << " collisions";
    if (o.check) {
      s << "; " << matched << " recorded states compared: all identical";
      if (paused > 0)
        s << " (" << paused << " more were published while paused, at stamps of no step)";
    }
    s << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options options =
        mm::runner::parseOptions(std::vector<std::string>(argv + 1, argv + argc));
    if (options.help) {
      printHelp(std::cout);
      return 0;
    }
    if (options.bag.empty()) throw UsageError("--bag: required (see resimulate --help)");
    return rerun(options);
  } catch (const UsageError& e) {
    std::cerr << "resimulate: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "resimulate: " << e.what() << "\n";
    return 1;
  }
}
