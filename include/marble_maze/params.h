// Every scene and physics value, with one table of keys shared by maze files, the runner's
// --set KEY=VALUE and the ROS node's private parameters.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "marble_maze/exact_text.h"
#include "marble_maze/geometry.h"

namespace marble_maze {

/// The contact model. Smooth is the seed's frictionless sliding sphere; Rolling is a solid sphere
/// (inertia 2/5 m r^2) with Coulomb friction, which slips and then rolls.
enum class Model { Smooth, Rolling };

/// How velocity and position advance over a step (see integrator.h).
enum class IntegratorKind { SemiImplicitEuler, VelocityVerlet, RungeKutta4 };

struct Params {
  // Marble.
  double marble_radius = 0.006;    ///< m (a 12 mm steel ball)
  double marble_density = 7850.0;  ///< kg/m^3 (steel)

  // Physics model; a feature at zero costs nothing in the step.
  Model model = Model::Rolling;
  double gravity = 9.81;              ///< m/s^2, along -z of the world
  double restitution = 0.5;           ///< coefficient e of eq. (1), 0..1
  bool bounce_threshold_auto = true;  ///< the threshold follows the step (bounceThreshold())
  double bounce_threshold = 0.02;     ///< m/s: slower approaches are contacts, not bounces
  double friction = 0.3;              ///< Coulomb coefficient (rolling model)
  double rolling_resistance = 0.0;    ///< dimensionless coefficient; 0 switches it off
  double drag_coefficient = 0.0;      ///< sphere drag coefficient C_d; 0 switches air drag off
  double air_density = 1.204;         ///< kg/m^3

  // Time stepping.
  double step = 0.001;  ///< s, the fixed step of Simulation::step()
  int substeps = 1;     ///< substeps per step
  IntegratorKind integrator = IntegratorKind::VelocityVerlet;
  std::string preset = "none";  ///< the last preset applied (see the key `preset`)

  // Board.
  double tilt_limit = 0.17453292519943295;  ///< rad (10 degrees): |roll|, |pitch| never exceed it
  double tilt_rate_limit = 2.0;  ///< rad/s, 0 = unlimited (a board that snaps flings the marble)
  double tilt_response_time = 0.05;  ///< s, time constant of the drive towards a target; 0 = none
  double initial_roll = 0.0;         ///< rad
  double initial_pitch = 0.0;        ///< rad

  /// m, world: where the board's pivot (the centre of its floor's top surface) is.
  Vec3 board_position = Vec3::Zero();

  // Start state; without start_position the marble starts on the maze's start cell.
  bool has_start_position = false;
  Vec3 start_position = Vec3::Zero();  ///< m, board frame
  Vec3 start_velocity = Vec3::Zero();  ///< m/s, world frame

  double marbleMass() const;
  double marbleInertia() const;  ///< about any axis through the centre
  /// The bounce threshold in force: the one set, or by default 0.02 m/s, raised for semi-implicit
  /// Euler to 2 g step/substeps (whose lagging velocity would otherwise bounce a resting marble).
  double bounceThreshold() const;
  /// The least bounce threshold the integrator and the substep allow.
  double leastBounceThreshold() const;
  /// The fastest a step resolves (m/s): 1e5 radii a step. The sweep walks a step's path in at
  /// most a million pieces of a radius; a faster marble could pass a wall unseen.
  double mostSpeed() const { return 1e5 * marble_radius / step; }
  /// "" for a speed (m/s) a step resolves, else why not: "S m/s is more than the M m/s (1e5
  /// radii a step) that a step resolves".
  std::string whyTooFast(double speed) const;
};

/// A bad key or value; the message names the key and what was expected.
struct ParamError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// One settable key: its name, unit, one line of help, and what it accepts (from which the
/// node's dynamic_reconfigure description is made).
struct ParamInfo {
  enum class Type { Number, Whole, Choice, Text };
  std::string key;
  std::string unit;
  std::string help;
  Type type = Type::Text;
  double min = 0, max = 0;           ///< Number and Whole: the accepted range
  std::vector<std::string> choices;  ///< Choice: the accepted names
  bool live = false;                 ///< may change while a simulation runs (Simulation::setParams)
};

/// Every key, in the order the help lists them.
const std::vector<ParamInfo>& paramInfos();

/// Sets one key from text ("0.7", "rolling", "0.1,0,0.006"); throws ParamError naming the key.
void setParam(Params& params, const std::string& key, const std::string& value);

/// The key's current value as text, in the form setParam accepts.
std::string getParam(const Params& params, const std::string& key);

/// Every key's value as lines "key=value", in the table's order, each reading back exactly (the
/// start position only when one is set).
std::string paramsText(const Params& params);

/// Params from paramsText's lines over `base`; throws ParamError naming a bad line.
Params paramsFromText(const std::string& text, Params base = Params());

/// The step a control period of `period` s is taken in: `step` where it divides the period into
/// whole steps (within 1e-9 of one), else the longest shorter one that does, so that every
/// period is honoured exactly (55 Hz at 1 ms: 19 steps of 0.957 ms; at 5 ms: 4 of 4.545 ms).
double stepDividing(double period, double step);

/// The most one command (an agent's action, a lockstep tilt, a `step` call) may take on, in steps
/// and in substeps: more would hold its caller up for seconds, or for ever.
constexpr std::uint32_t kMostStepsPerCommand = 10000000;
/// Why `steps` steps of `params` are more than one command may take on, or "". `asked` says what
/// asks for them, from the argument's name on.
std::string whyTooMuchWork(double steps, const Params& params, const std::string& asked);

/// "NAME: VALUE is out of range [MIN, MAX]", each number exact (a value just beyond a bound must
/// not read as the bound).
std::string outOfRangeText(const std::string& name, double value, double min, double max);

/// Reads a finite number that is the whole of `text` (spaces around it allowed); false otherwise,
/// also for a number too small to tell from 0 or too large for a double.
bool parseFiniteNumber(const std::string& text, double* value);
/// What is wrong with `text` as a finite number ("expected a number, got 'x'", "'1e-400'
/// underflows: ..."), or "" when nothing is.
std::string whyNotANumber(const std::string& text);

/// Checks the values together (ranges, step against threshold); throws ParamError naming the key.
void validate(const Params& params);

}  // namespace marble_maze
