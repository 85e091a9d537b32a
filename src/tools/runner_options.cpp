#include "runner_options.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <ostream>
#include <sstream>

#include "marble_maze/in_quotes.h"

namespace marble_maze {
namespace runner {

namespace {

/// Whether every key a physics refusal names ("KEY: why", or "KEY/KEY: why") was given by one of
/// `sets`: only then is it the --sets' to answer for (with one of them the maze file's, or a
/// default, it may be that one at fault).
bool namesOnlySetKeys(const std::vector<std::pair<std::string, std::string>>& sets,
                      const std::string& refusal) {
  std::istringstream keys(refusal.substr(0, refusal.find(": ")));
  std::string key;
  bool named = false;
  while (std::getline(keys, key, '/')) {
    if (std::none_of(sets.begin(), sets.end(), [&](const auto& set) { return set.first == key; }))
      return false;
    named = true;
  }
  return named;
}

}  // namespace

UsageError physicsRefusal(const Options& o, const ParamError& refusal,
                          const std::string& otherwise) {
  return UsageError((namesOnlySetKeys(o.sets, refusal.what()) ? "--set " : otherwise) +
                    std::string(refusal.what()));
}

void printHelp(std::ostream& out) {
  out <<
      R"(Usage: simulate [OPTION]...
Runs the marble_maze physics without ROS and reports what happened.

  --maze NAME|FILE     a built-in maze (classic, brio, prototype) or a maze file; default classic
  --tilt ROLL,PITCH    constant board tilt in radians (REP 103: roll about x, pitch about y);
                       default 0,0
  --tilt-csv FILE      tilt program: CSV rows t,roll,pitch (s, rad, rad), linear in between;
                       each step takes its value at the step's start
  --set KEY=VALUE      override a scene or physics value (repeatable); keys below
  --duration SECONDS   simulated time to run; default 5
  --out FILE           write the trajectory as CSV ('-' for standard output)
  --events FILE        write the events as CSV ('-' for standard output)
  --every N            write every Nth step to the trajectory; default 1
  --tilt-timeout S     after the tilt program's last row, the board holds its tilt S seconds,
                       then levels, as the node does without commands; default 0 (holds)
  --auto-reset S       S seconds after a hole or the goal the marble is put back on the start,
                       as the node's ~auto_reset does; default 0 (it stays)
  --quiet              no summary on standard output
  --help, -h           this text

Each flag that takes a value, but --set, is given once; --tilt and --tilt-csv not together.
A session recorded by record.launch is re-simulated by resimulate (resimulate --help).
The board starts at the tilt program's first value unless initial_roll or initial_pitch is set
(by --set or in the maze file's physics section).

Trajectory columns (world frame, SI units): t,x,y,z,vx,vy,vz,wx,wy,wz,roll,pitch,contacts,phase
  phase: free, in_hole, at_goal or off_board
Event columns: t,kind,i,j,k,speed   kind: collision, hole, goal or off_board; i,j,k the tile;
  speed: a collision's approach speed along the tile's normal, else the marble's speed

Keys for --set (and for a maze file's physics section):
)";
  for (const auto& info : paramInfos()) {
    const std::string name = info.key + (info.unit.empty() ? "" : " [" + info.unit + "]");
    char line[64];
    std::snprintf(line, sizeof line, "  %-26s ", name.c_str());
    // (The range is the table's, the one setParam refuses a value beyond.)
    const bool ranged = info.max > info.min;
    out << line << info.help
        << (ranged ? ", in [" + exactText(info.min) + ", " + exactText(info.max) + "]" : "")
        << " (default " << getParam(Params(), info.key) << ")\n";
  }
  out << "\nExit status: 0 done, 2 a wrong flag, value or maze file, 1 anything else.\n";
}

namespace {

double parseDouble(const std::string& flag, const std::string& text) {
  double value;
  if (!parseFiniteNumber(text, &value)) throw UsageError(flag + ": " + whyNotANumber(text));
  return value;
}

/// Whether two outputs are one: standard output twice, or one file by two names (/dev/null
/// twice is no harm).
bool sameOutput(const std::string& a, const std::string& b) {
  const auto name = [](const std::string& path) -> std::string {
    if (path == "-" || path == "/dev/stdout" || path == "/dev/fd/1" || path == "/proc/self/fd/1")
      return "-";
    std::error_code error;
    const std::filesystem::path canonical =
        std::filesystem::weakly_canonical(std::filesystem::absolute(path, error), error);
    return error ? path : canonical.string();
  };
  return a != "/dev/null" && name(a) == name(b);
}

}  // namespace

namespace {

/// The one value of a flag that takes one: a flag given again would silently undo the first.
const std::string* once(const std::string& flag, const std::vector<std::string>& values) {
  if (values.size() > 1)
    throw UsageError(flag + ": given twice (" + inQuotes(values[1]) + " after the first)");
  return values.empty() ? nullptr : &values.front();
}

double parseSeconds(const std::string& flag, const std::string& value) {
  const double seconds = parseDouble(flag, value);
  if (!(seconds >= 0 && seconds <= 1e6))
    throw UsageError(flag + ": expected 0..1e6 seconds, got " + inQuotes(value));
  return seconds;
}

std::pair<std::string, std::string> parseSet(const std::string& value) {
  const auto eq = value.find('=');
  if (eq == std::string::npos || eq == 0)
    throw UsageError("--set: expected KEY=VALUE, got " + inQuotes(value));
  std::pair<std::string, std::string> set(value.substr(0, eq), value.substr(eq + 1));
  // Its own value (a key none knows, a value out of its range) is the --set's whatever the
  // maze or bag it is set over.
  try {
    Params probe;
    setParam(probe, set.first, set.second);
  } catch (const ParamError& e) {
    throw UsageError("--set " + std::string(e.what()));
  }
  return set;
}

TiltSchedule parseTilt(const std::string& value) {
  const auto comma = value.find(',');
  if (comma == std::string::npos || value.find(',', comma + 1) != std::string::npos)
    throw UsageError("--tilt: expected ROLL,PITCH, got " + inQuotes(value));
  return TiltSchedule(parseDouble("--tilt", value.substr(0, comma)),
                      parseDouble("--tilt", value.substr(comma + 1)));
}

int parseEvery(const std::string& value) {
  const double n = parseDouble("--every", value);
  // Compared as doubles before any conversion: a cast of a number beyond int is undefined.
  constexpr double kMostEvery = std::numeric_limits<int>::max();
  if (n < 1 || n > kMostEvery || n != std::floor(n))
    throw UsageError("--every: expected a whole number from 1 to " +
                     std::to_string(std::numeric_limits<int>::max()) + ", got " + inQuotes(value));
  return static_cast<int>(n);
}

}  // namespace

Options parseOptions(const std::vector<std::string>& args) {
  Options o;
  CLI::App app;
  app.set_help_flag();  // --help is answered by the caller, whatever else the line holds
  app.allow_extras();   // an unknown flag is named below, as this tool names it
  app.add_flag("-h,--help", o.help);
  app.add_flag("--quiet", o.quiet);
  app.add_flag("--check", o.check);
  // Every value of every flag that takes one, each occurrence one value: checked below.
  std::map<std::string, std::vector<std::string>> given;
  for (const char* flag : {"--maze", "--tilt", "--tilt-csv", "--set", "--duration", "--out",
                           "--events", "--every", "--tilt-timeout", "--auto-reset", "--bag"})
    app.add_option(flag, given[flag])->allow_extra_args(false);
  try {
    app.parse(std::vector<std::string>(args.rbegin(), args.rend()));  // (CLI11 pops the back)
  } catch (const CLI::ArgumentMismatch& e) {  // "FLAG: 1 required TEXT missing"
    const std::string what = e.what();
    throw UsageError(what.substr(0, what.find(':')) + ": needs a value");
  } catch (const CLI::ParseError& e) {
    throw UsageError(std::string(e.what()) + " (see simulate --help)");
  }
  if (o.help) return o;
  const std::vector<std::string> extras = app.remaining();
  if (!extras.empty()) {
    const std::string& extra = extras.front();
    throw UsageError((extra.rfind("--", 0) == 0 ? "unknown option " : "unknown argument ") +
                     inQuotes(extra) + " (see simulate --help)");
  }
  const auto value = [&](const char* flag) { return once(flag, given[flag]); };
  if (const std::string* maze = value("--maze")) o.maze = *maze;
  // Each is the whole tilt program: the one would silently replace the other (the later named).
  const std::string *tilt = value("--tilt"), *tilt_csv = value("--tilt-csv");
  if (tilt && tilt_csv) {
    const auto later = std::find_if(
        app.parse_order().rbegin(), app.parse_order().rend(), [](const CLI::Option* option) {
          return option->get_name() == "--tilt" || option->get_name() == "--tilt-csv";
        });
    const bool csv_later = (*later)->get_name() == "--tilt-csv";
    throw UsageError(
        std::string(csv_later ? "--tilt-csv: not with --tilt" : "--tilt: not with --tilt-csv") +
        "; each gives the whole tilt program");
  }
  if (tilt) o.tilt = parseTilt(*tilt);
  if (tilt_csv) {
    try {
      o.tilt = TiltSchedule::load(*tilt_csv);
    } catch (const std::runtime_error& e) {
      throw UsageError(std::string("--tilt-csv: ") + e.what());
    }
  }
  for (const std::string& set : given["--set"]) o.sets.push_back(parseSet(set));
  if (const std::string* duration = value("--duration")) {
    o.duration = parseDouble("--duration", *duration);
    if (!(o.duration >= 0 && o.duration <= 1e6))
      throw UsageError("--duration: expected 0..1e6 seconds, got " + inQuotes(*duration));
  }
  if (const std::string* out = value("--out")) o.out = *out;
  if (const std::string* events = value("--events")) o.events = *events;
  if (const std::string* bag = value("--bag")) o.bag = *bag;
  if (const std::string* every = value("--every")) o.every = parseEvery(*every);
  if (const std::string* seconds = value("--tilt-timeout"))
    o.tilt_timeout = parseSeconds("--tilt-timeout", *seconds);
  if (const std::string* seconds = value("--auto-reset"))
    o.auto_reset = parseSeconds("--auto-reset", *seconds);
  // Two CSVs in one file, or both on standard output, would be one garbled CSV.
  if (!o.out.empty() && !o.events.empty() && sameOutput(o.out, o.events))
    throw UsageError("--events: '" + o.events + "' is --out's too; the trajectory and the " +
                     "events need a file each");
  // A recorded session brings its maze, its tilts and its length: a flag that would set them
  // again is refused rather than ignored.
  if (!o.bag.empty())
    for (const char* flag :
         {"--maze", "--tilt", "--tilt-csv", "--duration", "--tilt-timeout", "--auto-reset"})
      if (!given[flag].empty())
        throw UsageError(std::string(flag) + ": not with --bag, whose session sets it");
  // Other physics make other states: there is nothing the recording could confirm.
  if (o.check && !o.sets.empty())
    throw UsageError("--check: not with --set (" + o.sets.front().first +
                     "): the recorded states are those of the recorded physics");
  return o;
}

Run prepare(const Options& o) {
  if (o.check && o.bag.empty()) throw UsageError("--check: only with --bag");
  Run run;
  Scene& scene = run.scene;
  bool initial_tilt_set = false;
  const auto setsTilt = [](const std::string& key) {
    return key == "initial_roll" || key == "initial_pitch";
  };
  try {
    scene = loadScene(o.maze);
    for (const Scene::FileKey& set : scene.physics_keys)
      initial_tilt_set = initial_tilt_set || setsTilt(set.key);
    for (const auto& [key, value] : o.sets) {
      overrideParam(&scene, key, value);
      initial_tilt_set = initial_tilt_set || setsTilt(key);
    }
    // Clamped to the tilt limit as the node clamps a command, and said as the node says it.
    if (o.tilt.largestTilt() > scene.params.tilt_limit)
      std::cerr << "simulate: the tilt program asks for up to " << o.tilt.largestTilt()
                << " rad, beyond tilt_limit " << scene.params.tilt_limit << " rad; clamped\n";
    // The board starts where the tilt program starts (within the tilt limit, as every tilt), so
    // that a constant tilt is an incline from t = 0.
    if (!initial_tilt_set) {
      const double limit = scene.params.tilt_limit;
      scene.params.initial_roll = std::clamp(o.tilt.at(0).roll, -limit, limit);
      scene.params.initial_pitch = std::clamp(o.tilt.at(0).pitch, -limit, limit);
    }
    SessionSettings settings;
    settings.tilt_timeout = o.tilt_timeout;
    settings.auto_reset = o.auto_reset;
    run.session = std::make_unique<Session>(scene, settings);
  } catch (const MazeFileError& e) {
    throw UsageError(e.what());
  } catch (const ParamError& e) {  // values the maze file or --sets gave, refused together
    throw physicsRefusal(o, e, "");
  }
  return run;
}

void playStep(const Options& o, Run* run) {
  Session& session = *run->session;
  const double start = static_cast<double>(session.steps()) * run->scene.params.step;
  if (start <= o.tilt.duration()) {
    const TiltSchedule::Point tilt = o.tilt.at(start, &run->tilt_row);
    TiltCommand command;
    command.step = session.steps();
    command.roll = tilt.roll;
    command.pitch = tilt.pitch;
    session.command(command);
  }
  session.run(1);
}

}  // namespace runner
}  // namespace marble_maze
