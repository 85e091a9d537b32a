// simulate: the headless runner. Runs the physics core without ROS on a maze, under a constant
// tilt or a tilt program, and writes the trajectory as CSV and the events.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "../ros/recording.h"
#include "marble_maze/maze_file.h"
#include "marble_maze/simulation.h"
#include "marble_maze/tilt_schedule.h"
#include "runner_options.h"

namespace mm = marble_maze;
using mm::runner::Options;
using mm::runner::parseOptions;
using mm::runner::prepare;
using mm::runner::printHelp;
using mm::runner::Run;
using mm::runner::UsageError;

namespace {

const char* phaseName(mm::MarblePhase phase) {
  switch (phase) {
    case mm::MarblePhase::Free:
      return "free";
    case mm::MarblePhase::InHole:
      return "in_hole";
    case mm::MarblePhase::AtGoal:
      return "at_goal";
    case mm::MarblePhase::OffBoard:
      return "off_board";
  }
  return "unknown";
}

/// Where the summary goes: standard error when a CSV is written to standard output.
std::ostream& summaryStream(const Options& o) {
  return (o.out == "-" || o.events == "-") ? std::cerr : std::cout;
}

/// Opens FILE for writing, or standard output for "-"; null when no file was asked for.
std::ostream* openOutput(const std::string& path, std::unique_ptr<std::ofstream>* holder) {
  if (path.empty()) return nullptr;
  if (path == "-") return &std::cout;
  holder->reset(new std::ofstream(path));
  if (!**holder) throw UsageError("cannot write '" + path + "'");
  return holder->get();
}

/// The CSVs' first lines (their columns are in --help).
constexpr const char* kTrajectoryHeader = "t,x,y,z,vx,vy,vz,wx,wy,wz,roll,pitch,contacts,phase\n";
constexpr const char* kEventsHeader = "t,kind,i,j,k,speed\n";

void writeRow(std::ostream& out, const mm::Simulation& sim) {
  // Every value in its shortest form that reads back exactly (a position 1 km out keeps its
  // micrometres; bit-exact comparisons need it).
  const mm::Marble& m = sim.marble();
  out << mm::exactText(sim.time());
  const mm::Vec3 position = sim.worldPosition();
  for (const mm::Vec3* v : {&position, &m.velocity, &m.angular_velocity})
    for (int a = 0; a < 3; ++a) out << ',' << mm::exactText((*v)[a]);
  out << ',' << mm::exactText(sim.board().roll()) << ',' << mm::exactText(sim.board().pitch())
      << ',' << m.contacts << ',' << phaseName(m.phase) << '\n';
}

std::string describe(const mm::Event& e) {
  std::ostringstream text;
  text << mm::exactText(e.time) << ',' << mm::toString(e.kind) << ',' << e.tile.x() << ','
       << e.tile.y() << ',' << e.tile.z() << ',' << mm::exactText(e.speed);
  return text.str();
}

/// The events' rows in CSV, every number in its shortest form that reads back exactly.
void writeEvents(std::ostream* out, const std::vector<mm::Event>& events) {
  if (out)
    for (const mm::Event& e : events) *out << describe(e) << '\n';
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

/// Lists the events but collisions on `s`, one a line, and returns how many collisions there were.
int listFinishes(std::ostream& s, const std::vector<mm::Event>& events) {
  int collisions = 0;
  for (const mm::Event& e : events) {
    if (e.kind == mm::EventKind::Collision) {
      ++collisions;
      continue;
    }
    s << "  t=" << e.time << " s: " << mm::toString(e.kind) << " at tile (" << e.tile.x() << ", "
      << e.tile.y() << ", " << e.tile.z() << ")\n";
  }
  return collisions;
}

/// simulate --bag: the recorded session again, and with --check the comparison.
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
  std::ostream* out = openOutput(o.out, &out_file);
  std::ostream* events = openOutput(o.events, &events_file);
  const mm::Simulation& sim = replay->session().simulation();
  if (out) {
    *out << kTrajectoryHeader;
    writeRow(*out, sim);
  }
  if (events) *events << kEventsHeader;
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
        std::cerr << "simulate: --check: the state stamped " << stamp << " s (simulated time "
                  << mm::exactText(sim.time()) << " s, step " << sim.steps() << "): " << gap
                  << "\n";
        return 1;
      }
    }
    if (stamp >= end) break;
    replay->step();
    writeEvents(events, replay->session().events());
    all_events.insert(all_events.end(), replay->session().events().begin(),
                      replay->session().events().end());
    ++steps;
    if (out && (steps % o.every == 0)) writeRow(*out, sim);
  }
  if (out && steps % o.every != 0) writeRow(*out, sim);  // the last step, as a run writes it
  if (o.check && matched == 0) {
    std::cerr << "simulate: --check: " << o.bag
              << " holds no marble_state of the re-simulated steps: nothing to compare\n";
    return 1;
  }
  if (!o.quiet) {
    std::ostream& s = summaryStream(o);
    const int collisions = listFinishes(s, all_events);
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

int run(const Options& o) {
  if (!o.bag.empty()) return rerun(o);
  Run prepared = prepare(o);
  const mm::Scene& scene = prepared.scene;
  std::unique_ptr<mm::Simulation>& sim = prepared.sim;
  std::unique_ptr<std::ofstream> out_file, events_file;
  std::ostream* out = openOutput(o.out, &out_file);
  std::ostream* events = openOutput(o.events, &events_file);
  if (out) {
    *out << kTrajectoryHeader;
    writeRow(*out, *sim);
  }
  if (events) *events << kEventsHeader;
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
  std::size_t tilt_row = 0;
  for (std::uint64_t n = 1; n <= steps; ++n) {
    const mm::TiltSchedule::Point tilt = mm::runner::tiltBeforeStep(o, n, step, &tilt_row);
    sim->setTargetTilt(tilt.roll, tilt.pitch);
    sim->step();
    all_events.insert(all_events.end(), sim->events().begin(), sim->events().end());
    writeEvents(events, sim->events());
    if (out && (n % o.every == 0 || n == steps)) writeRow(*out, *sim);
  }
  if (!o.quiet) {
    std::ostream& s = summaryStream(o);
    const mm::Marble& m = sim->marble();
    const mm::Vec3 b = sim->marbleInBoard();
    s << "maze " << sim->maze().name() << ": " << sim->maze().size().x() << " x "
      << sim->maze().size().y() << " x " << sim->maze().size().z() << " tiles, model "
      << mm::getParam(scene.params, "model") << ", integrator "
      << mm::getParam(scene.params, "integrator") << ", step " << scene.params.step << " s x "
      << scene.params.substeps << "\n";
    const int collisions = listFinishes(s, all_events);
    s << "ran " << steps << " steps (" << sim->time() << " s): " << collisions
      << " collisions; marble " << phaseName(m.phase) << " at board (" << b.x() << ", " << b.y()
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
