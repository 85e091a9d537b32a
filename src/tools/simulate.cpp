// simulate: the headless runner. Runs the physics core without ROS on a maze, under a constant
// tilt or a tilt program, and writes the trajectory as CSV and the events.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "../ros/recording.h"
#include "marble_maze/maze_file.h"
#include "marble_maze/simulation.h"
#include "marble_maze/tilt_schedule.h"

namespace mm = marble_maze;

namespace {

/// A wrong flag or value: exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Options {
  std::string maze = "classic";
  mm::TiltSchedule tilt{0.0, 0.0};
  std::vector<std::pair<std::string, std::string>> sets;
  double duration = 5.0;
  std::string out;     // trajectory CSV, "-" for standard output
  std::string events;  // events CSV
  int every = 1;
  bool quiet = false;
  std::string bag;     // a recorded session to re-simulate
  bool check = false;  // and compare with its recorded marble_state
};

void printHelp() {
  std::cout <<
      R"(Usage: simulate [OPTION]...
Runs the marble_maze physics without ROS and reports what happened.

  --maze NAME|FILE     a built-in maze (classic, prototype) or a maze file; default classic
  --tilt ROLL,PITCH    constant board tilt in radians (REP 103: roll about x, pitch about y);
                       default 0,0
  --tilt-csv FILE      tilt program: CSV rows t,roll,pitch (s, rad, rad), linear in between
  --set KEY=VALUE      override a scene or physics value (repeatable); keys below
  --duration SECONDS   simulated time to run; default 5
  --out FILE           write the trajectory as CSV ('-' for standard output)
  --events FILE        write the events as CSV
  --every N            write every Nth step to the trajectory; default 1
  --quiet              no summary on standard output
  --bag FILE           re-simulate a session recorded by record.launch, from its first snapshot,
                       with its inputs at their steps (no ROS master needed); --set re-runs it
                       under other physics; --duration is ignored
  --check              with --bag: compare with the bag's recorded marble_state, bit for bit;
                       exit 1 at the first difference, printing its time and size
  --help               this text

The board starts at the tilt program's first value unless initial_roll or initial_pitch is set.

Trajectory columns (world frame, SI units): t,x,y,z,vx,vy,vz,wx,wy,wz,roll,pitch,contacts,phase
  phase: free, in_hole, at_goal or off_board
Event columns: t,kind,i,j,k,speed   kind: collision, hole, goal or off_board; i,j,k the tile

Keys for --set (and for a maze file's physics section):
)";
  for (const auto& info : mm::paramInfos()) {
    const std::string name = info.key + (info.unit.empty() ? "" : " [" + info.unit + "]");
    std::printf("  %-26s %s (default %s)\n", name.c_str(), info.help.c_str(),
                mm::getParam(mm::Params(), info.key).c_str());
  }
  std::cout << "\nExit status: 0 done, 2 a wrong flag, value or maze file, 1 anything else.\n";
}

double parseDouble(const std::string& flag, const std::string& text) {
  double value;
  if (!mm::parseFiniteNumber(text, &value))
    throw UsageError(flag + ": expected a number, got '" + text + "'");
  return value;
}

Options parseOptions(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--help" || flag == "-h") {
      printHelp();
      std::exit(0);
    }
    if (flag == "--quiet") {
      o.quiet = true;
      continue;
    }
    if (flag == "--check") {
      o.check = true;
      continue;
    }
    if (i + 1 >= argc)
      throw UsageError(flag +
                       (flag.rfind("--", 0) == 0 ? ": needs a value" : ": unknown argument"));
    const std::string value = argv[++i];
    if (flag == "--maze") {
      o.maze = value;
    } else if (flag == "--tilt") {
      const auto comma = value.find(',');
      if (comma == std::string::npos)
        throw UsageError("--tilt: expected ROLL,PITCH, got '" + value + "'");
      o.tilt = mm::TiltSchedule(parseDouble("--tilt", value.substr(0, comma)),
                                parseDouble("--tilt", value.substr(comma + 1)));
    } else if (flag == "--tilt-csv") {
      try {
        o.tilt = mm::TiltSchedule::load(value);
      } catch (const std::runtime_error& e) {
        throw UsageError(std::string("--tilt-csv: ") + e.what());
      }
    } else if (flag == "--set") {
      const auto eq = value.find('=');
      if (eq == std::string::npos || eq == 0)
        throw UsageError("--set: expected KEY=VALUE, got '" + value + "'");
      o.sets.emplace_back(value.substr(0, eq), value.substr(eq + 1));
    } else if (flag == "--duration") {
      o.duration = parseDouble(flag, value);
      if (!(o.duration >= 0 && o.duration <= 1e6))
        throw UsageError("--duration: expected 0..1e6 seconds, got '" + value + "'");
    } else if (flag == "--out") {
      o.out = value;
    } else if (flag == "--bag") {
      o.bag = value;
    } else if (flag == "--events") {
      o.events = value;
    } else if (flag == "--every") {
      const double n = parseDouble(flag, value);
      if (n < 1 || n != static_cast<int>(n))
        throw UsageError("--every: expected a whole number >= 1, got '" + value + "'");
      o.every = static_cast<int>(n);
    } else {
      throw UsageError("unknown option '" + flag + "' (see simulate --help)");
    }
  }
  return o;
}

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

/// Opens FILE for writing, or standard output for "-"; null when no file was asked for.
std::ostream* openOutput(const std::string& path, std::unique_ptr<std::ofstream>* holder) {
  if (path.empty()) return nullptr;
  if (path == "-") return &std::cout;
  holder->reset(new std::ofstream(path));
  if (!**holder) throw UsageError("cannot write '" + path + "'");
  return holder->get();
}

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
  char text[256];
  std::snprintf(text, sizeof text, "%.6f,%s,%d,%d,%d,%.6g", e.time, mm::toString(e.kind).c_str(),
                e.tile.x(), e.tile.y(), e.tile.z(), e.speed);
  return text;
}

/// The marble and the tilt at an instant: what a recorded state shows.
struct Shown {
  mm::Marble marble;
  double roll, pitch;
};

Shown shown(const mm::Simulation& sim) {
  return {sim.marble(), sim.board().roll(), sim.board().pitch()};
}

/// How a recorded state differs from what the simulation shows ("" when it is exactly it).
std::string differs(const marble_maze::MarbleState& recorded, const Shown& now) {
  const mm::Marble& m = now.marble;
  const auto vec = [](const auto& v) { return mm::Vec3(v.x, v.y, v.z); };
  const std::pair<const char*, double> gaps[] = {
      {"position", (vec(recorded.position) - m.position).norm()},
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

/// simulate --bag: the recorded session again, and with --check the comparison.
int rerun(const Options& o) {
  marble_maze_ros::Recording recording;
  std::unique_ptr<marble_maze_ros::Replayer> replay;
  try {
    recording = marble_maze_ros::readRecording(o.bag);
    replay = std::make_unique<marble_maze_ros::Replayer>(recording, o.sets);
  } catch (const mm::MazeFileError& e) {
    throw UsageError(std::string("--bag: ") + e.what());
  } catch (const mm::ParamError& e) {
    throw UsageError(std::string("--set ") + e.what());
  } catch (const std::runtime_error& e) {
    throw UsageError(std::string("--bag: ") + e.what());
  }
  std::unique_ptr<std::ofstream> out_file;
  std::ostream* out = openOutput(o.out, &out_file);
  const mm::Simulation& sim = replay->session().simulation();
  if (out) {
    *out << "t,x,y,z,vx,vy,vz,wx,wy,wz,roll,pitch,contacts,phase\n";
    writeRow(*out, sim);
  }
  const auto& states = recording.states;
  std::size_t next = 0, matched = 0, steps = 0;
  while (next < states.size() && states[next].header.stamp < replay->stamp()) ++next;
  const ros::Time end = replay->end();
  for (;;) {
    // A state recorded at this step's stamp shows the simulation before or after the inputs
    // that came between the steps (a reset shown at once).
    const Shown before = shown(sim);
    replay->applyDue();
    const ros::Time stamp = replay->stamp();
    for (; next < states.size() && states[next].header.stamp <= stamp; ++next) {
      if (states[next].header.stamp < stamp) continue;  // published while paused: not a step's
      ++matched;
      const std::string gap_before = differs(states[next], before);
      const std::string gap = differs(states[next], shown(sim));
      if (o.check && !gap_before.empty() && !gap.empty()) {
        std::cerr << "simulate: --check: at t=" << std::setprecision(17) << stamp.toSec()
                  << " s (step " << sim.steps() << "): " << gap << "\n";
        return 1;
      }
    }
    if (stamp >= end) break;
    replay->step();
    ++steps;
    if (out && (steps % o.every == 0)) writeRow(*out, sim);
  }
  if (!o.quiet) {
    std::ostream& s = (o.out == "-") ? std::cerr : std::cout;
    s << "re-simulated " << steps << " steps of " << o.bag << " from its first snapshot (step "
      << recording.snapshot.step << ")";
    if (o.check) s << "; " << matched << " recorded states compared: all identical";
    s << "\n";
  }
  return 0;
}

int run(const Options& o) {
  if (!o.bag.empty()) return rerun(o);
  if (o.check) throw UsageError("--check: only with --bag");
  mm::Scene scene;
  bool initial_tilt_set = false;
  try {
    scene = mm::loadScene(o.maze);
    for (const auto& [key, value] : o.sets) {
      mm::setParam(scene.params, key, value);
      initial_tilt_set = initial_tilt_set || key == "initial_roll" || key == "initial_pitch";
    }
  } catch (const mm::MazeFileError& e) {
    throw UsageError(e.what());
  } catch (const mm::ParamError& e) {
    throw UsageError(std::string("--set ") + e.what());
  }
  // The board starts where the tilt program starts (within the tilt limit, as every tilt), so
  // that a constant tilt is an incline from t = 0.
  if (!initial_tilt_set) {
    const double limit = scene.params.tilt_limit;
    scene.params.initial_roll = std::clamp(o.tilt.at(0).roll, -limit, limit);
    scene.params.initial_pitch = std::clamp(o.tilt.at(0).pitch, -limit, limit);
  }
  std::unique_ptr<mm::Simulation> sim;
  try {
    sim = std::make_unique<mm::Simulation>(scene);
  } catch (const mm::ParamError& e) {
    throw UsageError(e.what());
  }
  std::unique_ptr<std::ofstream> out_file, events_file;
  std::ostream* out = openOutput(o.out, &out_file);
  std::ostream* events = openOutput(o.events, &events_file);
  if (out) {
    *out << "t,x,y,z,vx,vy,vz,wx,wy,wz,roll,pitch,contacts,phase\n";
    writeRow(*out, *sim);
  }
  if (events) *events << "t,kind,i,j,k,speed\n";
  const auto steps = static_cast<std::uint64_t>(o.duration / scene.params.step + 0.5);
  std::vector<mm::Event> all_events;
  for (std::uint64_t n = 1; n <= steps; ++n) {
    const mm::TiltSchedule::Point tilt = o.tilt.at(static_cast<double>(n) * scene.params.step);
    sim->setTargetTilt(tilt.roll, tilt.pitch);
    sim->step();
    for (const mm::Event& e : sim->events()) {
      all_events.push_back(e);
      if (events) *events << describe(e) << '\n';
    }
    if (out && (n % o.every == 0 || n == steps)) writeRow(*out, *sim);
  }
  if (!o.quiet) {
    std::ostream& s = (o.out == "-") ? std::cerr : std::cout;
    const mm::Marble& m = sim->marble();
    const mm::Vec3 b = sim->marbleInBoard();
    s << "maze " << sim->maze().name() << ": " << sim->maze().size().x() << " x "
      << sim->maze().size().y() << " x " << sim->maze().size().z() << " tiles, model "
      << mm::getParam(scene.params, "model") << ", integrator "
      << mm::getParam(scene.params, "integrator") << ", step " << scene.params.step << " s x "
      << scene.params.substeps << "\n";
    int collisions = 0;
    for (const mm::Event& e : all_events) {
      if (e.kind == mm::EventKind::Collision) {
        ++collisions;
        continue;
      }
      s << "  t=" << e.time << " s: " << mm::toString(e.kind) << " at tile (" << e.tile.x() << ", "
        << e.tile.y() << ", " << e.tile.z() << ")\n";
    }
    s << "ran " << steps << " steps (" << sim->time() << " s): " << collisions
      << " collisions; marble " << phaseName(m.phase) << " at board (" << b.x() << ", " << b.y()
      << ", " << b.z() << ") m, speed " << m.velocity.norm() << " m/s\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parseOptions(argc, argv));
  } catch (const UsageError& e) {
    std::cerr << "simulate: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "simulate: " << e.what() << "\n";
    return 1;
  }
}
