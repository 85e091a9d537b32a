#include "marble_maze/params.h"

#include <cmath>
#include <functional>
#include <iomanip>
#include <limits>
#include <sstream>

namespace marble_maze {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

double parseNumber(const std::string& key, const std::string& text, double min, double max) {
  double value = 0;
  if (!parseFiniteNumber(text, &value))
    throw ParamError(key + ": expected a number, got '" + text + "'");
  if (value < min || value > max) {
    std::ostringstream msg;
    msg << key << ": " << value << " is out of range [" << min << ", " << max << "]";
    throw ParamError(msg.str());
  }
  return value;
}

Vec3 parseVec3(const std::string& key, const std::string& text) {
  Vec3 v;
  std::string rest = text;
  for (int a = 0; a < 3; ++a) {
    const auto comma = rest.find(',');
    if ((a < 2) != (comma != std::string::npos))
      throw ParamError(key + ": expected three comma-separated numbers X,Y,Z, got '" + text + "'");
    v[a] = parseNumber(key, rest.substr(0, comma), -kInf, kInf);
    rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
  }
  return v;
}

std::string format(double value) {
  std::ostringstream out;
  out << std::setprecision(10) << value;
  return out.str();
}

std::string format(const Vec3& v) {
  return format(v.x()) + "," + format(v.y()) + "," + format(v.z());
}

struct Entry {
  ParamInfo info;
  std::function<void(Params&, const std::string&)> set;
  std::function<std::string(const Params&)> get;
};

/// A number member with its allowed range.
Entry number(const char* key, const char* unit, const char* help, double Params::*member,
             double min, double max) {
  return {{key, unit, help},
          [=](Params& p, const std::string& text) { p.*member = parseNumber(key, text, min, max); },
          [=](const Params& p) { return format(p.*member); }};
}

const std::vector<Entry>& entries() {
  static const std::vector<Entry> table = {
      number("marble_radius", "m", "marble radius", &Params::marble_radius, 1e-4, 1.0),
      number("marble_density", "kg/m^3", "marble density (steel 7850)", &Params::marble_density,
             1.0, 1e5),
      {{"model", "",
        "contact model: smooth (frictionless, slides) or rolling (solid sphere, "
        "Coulomb friction)"},
       [](Params& p, const std::string& text) {
         if (text == "smooth")
           p.model = Model::Smooth;
         else if (text == "rolling")
           p.model = Model::Rolling;
         else
           throw ParamError("model: expected 'smooth' or 'rolling', got '" + text + "'");
       },
       [](const Params& p) {
         return std::string(p.model == Model::Smooth ? "smooth" : "rolling");
       }},
      number("gravity", "m/s^2", "gravitational acceleration", &Params::gravity, 0.0, 1000.0),
      number("restitution", "", "coefficient of restitution e of eq. (1)", &Params::restitution,
             0.0, 1.0),
      number("bounce_threshold", "m/s",
             "approach speeds below this are contacts (no bounce); at least 2 g step/substeps",
             &Params::bounce_threshold, 0.0, 100.0),
      number("friction", "", "Coulomb friction coefficient (rolling model)", &Params::friction, 0.0,
             10.0),
      number("rolling_resistance", "", "rolling resistance coefficient, 0 = off",
             &Params::rolling_resistance, 0.0, 1.0),
      number("drag_coefficient", "", "air drag coefficient C_d of the sphere, 0 = off",
             &Params::drag_coefficient, 0.0, 10.0),
      number("air_density", "kg/m^3", "air density for the drag", &Params::air_density, 0.0, 100.0),
      number("step", "s", "fixed time step", &Params::step, 1e-6, 0.1),
      {{"substeps", "", "substeps per step (1..1000)"},
       [](Params& p, const std::string& text) {
         const double n = parseNumber("substeps", text, 1, 1000);
         if (n != std::floor(n))
           throw ParamError("substeps: expected a whole number, got '" + text + "'");
         p.substeps = static_cast<int>(n);
       },
       [](const Params& p) { return std::to_string(p.substeps); }},
      {{"integrator", "", "time integrator: semi_implicit_euler"},
       [](Params& p, const std::string& text) {
         if (text != "semi_implicit_euler")
           throw ParamError("integrator: expected 'semi_implicit_euler', got '" + text + "'");
         p.integrator = Integrator::SemiImplicitEuler;
       },
       [](const Params&) { return std::string("semi_implicit_euler"); }},
      number("tilt_limit", "rad", "largest |roll| and |pitch| of the board", &Params::tilt_limit,
             0.0, kPi / 2),
      number("tilt_rate_limit", "rad/s", "largest tilt rate of the board, 0 = unlimited",
             &Params::tilt_rate_limit, 0.0, 1000.0),
      number("tilt_response_time", "s",
             "time constant with which the board follows a target tilt (a servo), 0 = at once",
             &Params::tilt_response_time, 0.0, 10.0),
      number("initial_roll", "rad", "board roll at the start", &Params::initial_roll, -kPi / 2,
             kPi / 2),
      number("initial_pitch", "rad", "board pitch at the start", &Params::initial_pitch, -kPi / 2,
             kPi / 2),
      {{"start_position", "m", "marble start X,Y,Z in the board frame"},
       [](Params& p, const std::string& text) {
         p.start_position = parseVec3("start_position", text);
         p.has_start_position = true;
       },
       [](const Params& p) {
         return p.has_start_position ? format(p.start_position) : "start cell";
       }},
      {{"start_velocity", "m/s", "marble start velocity VX,VY,VZ in the world frame"},
       [](Params& p, const std::string& text) {
         p.start_velocity = parseVec3("start_velocity", text);
       },
       [](const Params& p) { return format(p.start_velocity); }},
  };
  return table;
}

const Entry& find(const std::string& key) {
  for (const auto& e : entries())
    if (e.info.key == key) return e;
  std::string known;
  for (const auto& e : entries()) known += (known.empty() ? "" : ", ") + e.info.key;
  throw ParamError("unknown parameter '" + key + "' (known: " + known + ")");
}

}  // namespace

bool parseFiniteNumber(const std::string& text, double* value) {
  std::istringstream in(text);
  in >> *value;
  return !in.fail() && (in >> std::ws).eof() && std::isfinite(*value);
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

void validate(const Params& p) {
  const double h = p.step / p.substeps;
  // A resting marble gains g*h of approach speed every substep; a threshold below that would make
  // it bounce on the floor forever instead of resting.
  if (p.bounce_threshold < 2.0 * p.gravity * h) {
    std::ostringstream msg;
    msg << "bounce_threshold: " << p.bounce_threshold
        << " m/s is below 2 g step/substeps = " << 2.0 * p.gravity * h
        << " m/s; raise it or shorten the step";
    throw ParamError(msg.str());
  }
  if (std::abs(p.initial_roll) > p.tilt_limit || std::abs(p.initial_pitch) > p.tilt_limit)
    throw ParamError("initial_roll/initial_pitch: beyond tilt_limit " + format(p.tilt_limit));
}

}  // namespace marble_maze
