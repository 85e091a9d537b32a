#include "marble_maze/params.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iomanip>
#include <limits>
#include <sstream>
#include <utility>

#include "marble_maze/in_quotes.h"

namespace marble_maze {

std::string Params::whyTooFast(double speed) const {
  if (!(speed > mostSpeed())) return "";
  return exactText(speed) + " m/s is more than the " + exactText(mostSpeed()) +
         " m/s (1e5 radii a step) that a step resolves";
}

double stepDividing(double period, double step) {
  const double whole = std::round(period / step);
  if (whole >= 1 && std::abs(whole * step - period) <= 1e-9 * period) return step;
  return period / std::ceil(period / step);
}

std::string whyTooMuchWork(double steps, const Params& params, const std::string& asked) {
  const std::string most = std::to_string(kMostStepsPerCommand);
  if (!(steps <= kMostStepsPerCommand)) return asked + " more than " + most + " steps a command";
  if (!(steps * params.substeps <= kMostStepsPerCommand))
    return asked + " (of " + std::to_string(params.substeps) + " substeps each) more than " + most +
           " substeps a command";
  return "";
}

std::string outOfRangeText(const std::string& name, double value, double min, double max) {
  return name + ": " + exactText(value) + " is out of range [" + exactText(min) + ", " +
         exactText(max) + "]";
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double parseNumber(const std::string& key, const std::string& text, double min, double max) {
  double value = 0;
  if (!parseFiniteNumber(text, &value)) throw ParamError(key + ": " + whyNotANumber(text));
  if (value < min || value > max) throw ParamError(outOfRangeText(key, value, min, max));
  return value;
}

Vec3 parseVec3(const std::string& key, const std::string& text) {
  Vec3 v;
  // "X,Y,Z", or the list "[X, Y, Z]" that ROS hands a node for _key:=[X, Y, Z] on its command
  // line (roscpp does not read a list there: the node gets the text).
  std::string rest = text;
  const auto first = rest.find_first_not_of(" \t"), last = rest.find_last_not_of(" \t");
  if (first != std::string::npos && rest[first] == '[' && rest[last] == ']')
    rest = rest.substr(first + 1, last - first - 1);
  for (int a = 0; a < 3; ++a) {
    const auto comma = rest.find(',');
    if ((a < 2) != (comma != std::string::npos))
      throw ParamError(key + ": expected three comma-separated numbers X,Y,Z, got " +
                       inQuotes(text));
    v[a] = parseNumber(key, rest.substr(0, comma), -kInf, kInf);
    rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
  }
  return v;
}

std::string format(double value) {
  return exactText(value);
}

std::string format(const Vec3& v) {
  return format(v.x()) + "," + format(v.y()) + "," + format(v.z());
}

/// "'a', 'b' or 'c'" from the names of a list of pairs.
template <typename T>
std::string listOf(const std::vector<std::pair<std::string, T>>& names) {
  std::string text;
  for (std::size_t i = 0; i < names.size(); ++i)
    text += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + ("'" + names[i].first + "'");
  return text;
}

constexpr double kMostBounceThreshold = 100;  // m/s
constexpr double kMostSubsteps = 1000;

struct Entry {
  ParamInfo info;
  std::function<void(Params&, const std::string&)> set;
  std::function<std::string(const Params&)> get;
  std::function<double(const Params&)> number;  // Number and Whole keys: the value, to check
};

/// A number member with its allowed range.
Entry number(const char* key, const char* unit, const char* help, double Params::*member,
             double min, double max) {
  return {{key, unit, help, ParamInfo::Type::Number, min, max, {}, false},
          [=](Params& p, const std::string& text) { p.*member = parseNumber(key, text, min, max); },
          [=](const Params& p) { return format(p.*member); },
          [=](const Params& p) { return p.*member; }};
}

/// A key given as free text (a vector's "X,Y,Z", a number or "auto"), set and read back by the
/// functions given; the range [min, max] of a number it may be (none when they are equal).
Entry textKey(const char* key, const char* unit, const char* help,
              std::function<void(Params&, const std::string&)> set,
              std::function<std::string(const Params&)> get, double min = 0, double max = 0) {
  return {{key, unit, help, ParamInfo::Type::Text, min, max, {}, false},
          std::move(set),
          std::move(get),
          {}};
}

/// The entry, marked as one that may change while a simulation runs.
Entry live(Entry entry) {
  entry.info.live = true;
  return entry;
}

/// A member with named values; an unknown name is refused with the list of accepted ones.
template <typename T>
Entry choice(const char* key, const char* help, T Params::*member,
             std::vector<std::pair<std::string, T>> names) {
  std::vector<std::string> choices;
  choices.reserve(names.size());
  for (const auto& named : names) choices.push_back(named.first);
  return {{key, "", help, ParamInfo::Type::Choice, 0, 0, choices, false},
          [=](Params& p, const std::string& text) {
            for (const auto& [name, value] : names)
              if (name == text) {
                p.*member = value;
                return;
              }
            throw ParamError(std::string(key) + ": expected one of " + listOf(names) + ", got " +
                             inQuotes(text));
          },
          [=](const Params& p) {
            for (const auto& [name, value] : names)
              if (value == p.*member) return name;
            return std::string("?");
          },
          {}};
}

/// The presets: integrator, step, substeps and model for each use (measured by make tradeoff);
/// `realistic` also takes the real game's measured physics (measuredPhysics()).
struct Preset {
  const char* name;
  IntegratorKind integrator;
  double step;
  int substeps;
  Model model;
  bool measured_physics;
};
const Preset kPresets[] = {
    {"realtime", IntegratorKind::VelocityVerlet, 0.001, 1, Model::Rolling, false},
    {"fast", IntegratorKind::VelocityVerlet, 0.005, 1, Model::Rolling, false},
    {"accurate", IntegratorKind::RungeKutta4, 0.0001, 1, Model::Rolling, false},
    {"realistic", IntegratorKind::VelocityVerlet, 0.001, 1, Model::Rolling, true},
};

/// The wooden labyrinth game as measured; each value and its source in doc/realistic.md.
void measuredPhysics(Params& p) {
  p.marble_radius = 0.00635;  // a 12.7 mm ball
  // 9 g in a 12.7 mm ball: 0.009 kg / (4/3 pi 0.00635^3 m^3)
  p.marble_density = 0.009 / (4.0 / 3.0 * kPi * std::pow(0.00635, 3));
  p.rolling_resistance = 0.00118;
  p.restitution = 0.11;  // the walls' bounce factor
  p.tilt_limit = 10 * kPi / 180;
}

void applyPreset(Params& p, const std::string& name) {
  if (name == "none") {
    p.preset = name;
    return;
  }
  for (const Preset& preset : kPresets) {
    if (name != preset.name) continue;
    p.integrator = preset.integrator;
    p.step = preset.step;
    p.substeps = preset.substeps;
    p.model = preset.model;
    if (preset.measured_physics) measuredPhysics(p);
    p.preset = name;
    return;
  }
  std::vector<std::pair<std::string, const Preset*>> names;
  for (const Preset& preset : kPresets) names.emplace_back(preset.name, &preset);
  names.emplace_back("none", nullptr);
  throw ParamError("preset: expected one of " + listOf(names) + ", got " + inQuotes(name));
}

const std::vector<Entry>& entries() {
  static const std::vector<Entry> table = {
      {{"preset",
        "",
        "sets integrator, step, substeps and model for a use: realtime (a ROS graph "
        "controlling at ~55 Hz), fast (training agents), accurate (closest to the physics), "
        "realistic (realtime with the real game's measured marble, rolling resistance, wall "
        "bounce and tilt limit), none; keys set after it override it",
        ParamInfo::Type::Choice,
        0,
        0,
        {"realtime", "fast", "accurate", "realistic", "none"},
        false},
       [](Params& p, const std::string& text) { applyPreset(p, text); },
       [](const Params& p) { return p.preset; },
       {}},
      number("marble_radius", "m", "marble radius", &Params::marble_radius, 1e-4, 1.0),
      number("marble_density", "kg/m^3", "marble density (steel 7850)", &Params::marble_density,
             1.0, 1e5),
      live(choice("model",
                  "contact model: smooth (frictionless, slides) or rolling (solid sphere, "
                  "Coulomb friction)",
                  &Params::model, {{"smooth", Model::Smooth}, {"rolling", Model::Rolling}})),
      number("gravity", "m/s^2", "gravitational acceleration", &Params::gravity, 0.0, 1000.0),
      live(number("restitution", "", "coefficient of restitution e of eq. (1)",
                  &Params::restitution, 0.0, 1.0)),
      textKey(
          "bounce_threshold", "m/s",
          "approach speeds below this are contacts, not bounces; auto: 0.02, and for "
          "semi_implicit_euler at least 2 g step/substeps",
          [](Params& p, const std::string& text) {
            p.bounce_threshold_auto = text == "auto";
            if (!p.bounce_threshold_auto)
              p.bounce_threshold = parseNumber("bounce_threshold", text, 0.0, kMostBounceThreshold);
          },
          [](const Params& p) {
            return p.bounce_threshold_auto ? std::string("auto") : format(p.bounce_threshold);
          },
          0.0, kMostBounceThreshold),
      live(number("friction", "", "Coulomb friction coefficient (rolling model)", &Params::friction,
                  0.0, 10.0)),
      live(number("rolling_resistance", "", "rolling resistance coefficient, 0 = off",
                  &Params::rolling_resistance, 0.0, 1.0)),
      live(number("drag_coefficient", "", "air drag coefficient C_d of the sphere, 0 = off",
                  &Params::drag_coefficient, 0.0, 10.0)),
      number("air_density", "kg/m^3", "air density for the drag", &Params::air_density, 0.0, 100.0),
      live(number("step", "s", "fixed time step", &Params::step, 1e-6, 0.1)),
      {{"substeps", "", "substeps per step", ParamInfo::Type::Whole, 1, kMostSubsteps, {}, true},
       [](Params& p, const std::string& text) {
         const double n = parseNumber("substeps", text, 1, kMostSubsteps);
         if (n != std::floor(n))
           throw ParamError("substeps: expected a whole number, got " + inQuotes(text));
         p.substeps = static_cast<int>(n);
       },
       [](const Params& p) { return std::to_string(p.substeps); },
       [](const Params& p) { return static_cast<double>(p.substeps); }},
      live(choice("integrator",
                  "time integrator: semi_implicit_euler (first order, cheapest), velocity_verlet "
                  "(second order, exact under constant forces), rk4 (fourth order, for air drag)",
                  &Params::integrator,
                  {{"semi_implicit_euler", IntegratorKind::SemiImplicitEuler},
                   {"velocity_verlet", IntegratorKind::VelocityVerlet},
                   {"rk4", IntegratorKind::RungeKutta4}})),
      live(number("tilt_limit", "rad", "largest |roll| and |pitch| of the board",
                  &Params::tilt_limit, 0.0, kQuarterTurn)),
      live(number("tilt_rate_limit", "rad/s", "largest tilt rate of the board, 0 = unlimited",
                  &Params::tilt_rate_limit, 0.0, 1000.0)),
      live(number("tilt_response_time", "s",
                  "time constant with which the board follows a target tilt (a servo), 0 = at "
                  "once",
                  &Params::tilt_response_time, 0.0, 10.0)),
      number("initial_roll", "rad", "board roll at the start", &Params::initial_roll, -kQuarterTurn,
             kQuarterTurn),
      number("initial_pitch", "rad", "board pitch at the start", &Params::initial_pitch,
             -kQuarterTurn, kQuarterTurn),
      textKey(
          "board_position", "m", "where the board's pivot is in the world: X,Y,Z",
          [](Params& p, const std::string& text) {
            p.board_position = parseVec3("board_position", text);
          },
          [](const Params& p) { return format(p.board_position); }),
      textKey(
          "start_position", "m", "marble start X,Y,Z in the board frame",
          [](Params& p, const std::string& text) {
            p.start_position = parseVec3("start_position", text);
            p.has_start_position = true;
          },
          [](const Params& p) {
            return p.has_start_position ? format(p.start_position) : "start cell";
          }),
      textKey(
          "start_velocity", "m/s", "marble start velocity VX,VY,VZ in the world frame",
          [](Params& p, const std::string& text) {
            p.start_velocity = parseVec3("start_velocity", text);
          },
          [](const Params& p) { return format(p.start_velocity); }),
  };
  return table;
}

const Entry& find(const std::string& key) {
  for (const auto& e : entries())
    if (e.info.key == key) return e;
  std::string known;
  for (const auto& e : entries()) known += (known.empty() ? "" : ", ") + e.info.key;
  // (Named first, as every other refusal of a key is: "KEY: what is wrong".)
  throw ParamError(inQuotes(key) + ": unknown parameter (known: " + known + ")");
}

}  // namespace

namespace {

enum class NumberText { Finite, NotANumber, Underflows, Overflows, NotFinite };

/// Reads the whole of `text` (spaces around it allowed) as a number, telling what is wrong with it
/// when it is not a finite one.
NumberText readNumberText(const std::string& text, double* value) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double read = std::strtod(begin, &end);
  if (end == begin) return NumberText::NotANumber;
  while (end < begin + text.size() && std::isspace(static_cast<unsigned char>(*end))) ++end;
  if (end != begin + text.size()) return NumberText::NotANumber;
  if (errno == ERANGE)
    return std::abs(read) <= std::numeric_limits<double>::min() ? NumberText::Underflows
                                                                : NumberText::Overflows;
  if (!std::isfinite(read)) return NumberText::NotFinite;
  *value = read;
  return NumberText::Finite;
}

}  // namespace

bool parseFiniteNumber(const std::string& text, double* value) {
  return readNumberText(text, value) == NumberText::Finite;
}

std::string whyNotANumber(const std::string& text) {
  double value = 0;
  switch (readNumberText(text, &value)) {
    case NumberText::Finite:
      return "";
    case NumberText::Underflows:
      return inQuotes(text) +
             " underflows: it is too small to tell from 0 (the least is about 2.2e-308)";
    case NumberText::Overflows:
      return inQuotes(text) + " overflows: it is beyond the largest number (about 1.8e308)";
    case NumberText::NotFinite:
      return "expected a finite number, got " + inQuotes(text);
    case NumberText::NotANumber:
      break;
  }
  return "expected a number, got " + inQuotes(text);
}

double Params::marbleMass() const {
  return marble_density * 4.0 / 3.0 * kPi * marble_radius * marble_radius * marble_radius;
}

double Params::marbleInertia() const {
  return 0.4 * marbleMass() * marble_radius * marble_radius;
}

const std::vector<ParamInfo>& paramInfos() {
  static const std::vector<ParamInfo> infos = [] {
    std::vector<ParamInfo> result;
    for (const auto& e : entries()) result.push_back(e.info);
    return result;
  }();
  return infos;
}

void setParam(Params& params, const std::string& key, const std::string& value) {
  find(key).set(params, value);
}

std::string getParam(const Params& params, const std::string& key) {
  return find(key).get(params);
}

std::string paramsText(const Params& params) {
  std::string text;
  for (const auto& e : entries()) {
    if (e.info.key == "start_position" && !params.has_start_position) continue;
    text += e.info.key + "=" + e.get(params) + "\n";
  }
  return text;
}

Params paramsFromText(const std::string& text, Params base) {
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.empty()) continue;
    const auto eq = line.find('=');
    if (eq == std::string::npos) throw ParamError("expected key=value, got " + inQuotes(line));
    setParam(base, line.substr(0, eq), line.substr(eq + 1));
  }
  return base;
}

double Params::leastBounceThreshold() const {
  // Semi-implicit Euler's velocity lags its position by half a substep: a marble a hair above
  // the floor meets it at up to g h faster than it truly does, and would bounce on it forever
  // below 2 g h. The other schemes meet the floor at the true speed and need no least value.
  if (integrator != IntegratorKind::SemiImplicitEuler) return 0;
  return 2.0 * gravity * step / substeps;
}

double Params::bounceThreshold() const {
  return bounce_threshold_auto ? std::max(0.02, leastBounceThreshold()) : bounce_threshold;
}

void validate(const Params& p) {
  // Each number within its key's range: values set as text were checked as they were read, but
  // a program can fill Params directly.
  for (const Entry& e : entries()) {
    if (!e.number) continue;
    const double value = e.number(p);
    if (!(value >= e.info.min && value <= e.info.max))
      throw ParamError(outOfRangeText(e.info.key, value, e.info.min, e.info.max));
  }
  if (p.bounceThreshold() < p.leastBounceThreshold()) {
    throw ParamError("bounce_threshold: " + exactText(p.bounceThreshold()) +
                     " m/s is below 2 g step/substeps = " + exactText(p.leastBounceThreshold()) +
                     " m/s, which semi_implicit_euler needs; raise it, shorten the step or leave "
                     "it auto");
  }
  const std::string too_fast = p.whyTooFast(p.start_velocity.stableNorm());
  if (!too_fast.empty()) throw ParamError("start_velocity: " + too_fast);
  if (std::abs(p.initial_roll) > p.tilt_limit || std::abs(p.initial_pitch) > p.tilt_limit)
    throw ParamError("initial_roll/initial_pitch: beyond tilt_limit " + format(p.tilt_limit));
}

}  // namespace marble_maze
