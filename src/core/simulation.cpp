#include "marble_maze/simulation.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "marble_maze/rotation.h"

namespace marble_maze {
namespace {

// Contacts are looked for this far beyond the marble's surface: far below anything visible, and
// above the gap that a turning board opens under a marble it carries in one step (its rotation,
// second order in the step: some nanometres), so that such a marble stays in contact instead of
// meeting the board anew every other step.
constexpr double kContactMargin = 1e-7;  // m
// A marble wedged in a corner meets a few impacts in one substep; beyond these it stays put.
constexpr int kMaxImpactsPerSubstep = 4;
// Slower than this across a contact the marble rests on it (what the contact solver leaves of a
// velocity it stopped); faster, and faster than the surface under it changes its normal velocity
// over the stretch, it is leaving, and may come back within the step.
constexpr double kRestingSpeed = 1e-5;  // m/s
// The tiles near the marble are gathered this many radii farther than a substep needs, and kept
// until it has moved that far: at play speeds (up to about 1 m/s) that lasts several substeps,
// and the box they are gathered from grows by few tiles.
constexpr double kNearSlack = 0.5;
// The highest above the board's floor (m) a marble may be put: a fall of 4.5 s.
constexpr double kMostPlacedHeight = 100;
// The most a board turns in one substep (rad): beyond it a step is cut into more substeps.
constexpr double kMostTurn = 0.05;
// The substep's path relative to a turning board is swept as a chord of its arc: a turn of a
// about the pivot, at a reach L from it, leaves the arc L a^2 / 8 off the chord. The turn is
// kept small enough that this stays within this share of the marble's radius.
constexpr double kMostChordGap = 0.0025;
// The most air drag may slow the marble in one substep, k |v| h: within it every scheme slows it
// without overshooting (explicit Euler's limit is 1); beyond it a step is cut into more substeps.
constexpr double kMostDragDecay = 0.5;

/// Why a free marble moves faster than a step of `params` resolves, as place and start_velocity
/// refuse it, or "" (a held one moves with the board, as fast as its place makes it).
std::string whyTooFast(const Marble& m, const Params& params) {
  if (m.phase != MarblePhase::Free) return "";
  const std::string linear = params.whyTooFast(m.velocity.stableNorm());
  if (!linear.empty()) return "speed " + linear;
  const std::string surface =
      params.whyTooFast(m.angular_velocity.stableNorm() * params.marble_radius);
  return surface.empty() ? "" : "surface's speed from its spin, " + surface;
}

/// Why steps of `step` cannot time the simulated time `time` closely enough for the timed
/// actions (2^50 of them or more: at 1 ms some 36,000 years, which no session runs), or "".
std::string whyTooManySteps(double time, double step) {
  if (std::abs(time) < 0x1p50 * step) return "";
  return "the simulated time " + exactText(time) + " s is 2^50 steps of " + exactText(step) +
         " s or more";
}

/// The most the board may turn in one substep (rad): kMostTurn, or less where the board reaches
/// so far from its pivot, against the marble's size, that the arc of a turn would stray from its
/// chord by more than kMostChordGap of the radius (a 0.5 mm marble in metre cells).
double mostTurnFor(const Maze& maze, const Params& params) {
  const Vec3 reach = maze.pivot().cwiseMax(maze.extent() - maze.pivot());
  const double most = std::sqrt(8 * kMostChordGap * params.marble_radius / reach.norm());
  return std::min(kMostTurn, most);
}

}  // namespace

Simulation::Simulation(const Scene& scene)
    : maze_(scene.maze),
      params_(scene.params),
      board_(params_),
      solver_(params_),
      forces_(params_),
      integrator_(&integratorFor(params_.integrator)),
      mass_(params_.marbleMass()),
      inertia_(params_.marbleInertia()),
      most_turn_(mostTurnFor(maze_, params_)) {
  validate(params_);
  substep_ = params_.step / params_.substeps;
  reset();
  // The marble must start where it can be: not in a tile (a start position in a wall, a marble
  // wider than its start cell) and on the board.
  const std::string why = whyNotPlaceable(startInBoard());
  if (!why.empty()) {
    std::ostringstream message;
    std::string key;
    if (params_.has_start_position) {
      // (The radius said too: a radius set over the file's can be what keeps the marble out.)
      key = "start_position";
      message << key << ": a marble of radius " << exactText(params_.marble_radius)
              << " m cannot start there: " << why;
    } else {
      key = "marble_radius";
      message << key << ": a marble of radius " << params_.marble_radius
              << " m does not fit the start cell (" << maze_.start().i << ", " << maze_.start().j
              << (scene.start_in_file.empty() ? "" : ", the 'S' at " + scene.start_in_file)
              << "): " << why;
    }
    // Set by the maze file: the error points at it there, as the file's other errors do.
    if (const Scene::FileKey* set = findFileKey(scene, key))
      throw MazeFileError(scene.source, set->line, set->column, message.str());
    throw ParamError(message.str());
  }
}

void Simulation::setParams(const Params& params) {
  validate(params);
  // A free marble stays one a step resolves, as place requires and a snapshot's restore checks.
  const std::string too_fast = whyTooFast(marble_, params);
  if (!too_fast.empty()) throw ParamError("step/marble_radius: the marble's " + too_fast);
  const std::string too_many = whyTooManySteps(time_, params.step);
  if (!too_many.empty()) throw ParamError("step: " + too_many);
  params_ = params;
  board_.setLimits(params_);
  counts_.pairs += solver_.pairCounts();  // (counts() adds the new solver's)
  solver_ = ContactSolver(params_);
  forces_ = FieldForces(params_);
  integrator_ = &integratorFor(params_.integrator);
  mass_ = params_.marbleMass();
  inertia_ = params_.marbleInertia();
  most_turn_ = mostTurnFor(maze_, params_);
  frame_ = gridFrame();
  substep_ = params_.step / params_.substeps;
  time_origin_ = time_;  // steps of another length count from here
  steps_origin_ = steps_;
  resting_ = false;
}

SimulationState Simulation::state() const {
  return {marble_, board_, held_in_grid_, time_, steps_};
}

void Simulation::restore(const SimulationState& state) {
  const std::string too_many = whyTooManySteps(state.time, params_.step);
  if (!too_many.empty()) throw ParamError("step: " + too_many);
  marble_ = state.marble;
  board_ = state.board;
  board_.setLimits(params_);
  held_in_grid_ = state.held_in_grid;
  time_ = time_origin_ = state.time;
  steps_ = steps_origin_ = state.steps;
  frame_ = gridFrame();
  board_work_ = 0;
  resting_ = false;
  events_.clear();
}

void Simulation::save(ByteWriter* out) const {
  out->put(marble_.position);
  out->put(marble_.velocity);
  out->put(marble_.angular_velocity);
  for (double c : {marble_.orientation.w(), marble_.orientation.x(), marble_.orientation.y(),
                   marble_.orientation.z()})
    out->put(c);
  out->put(static_cast<std::int32_t>(marble_.phase));
  out->put(static_cast<std::int32_t>(marble_.contacts));
  board_.save(out);
  out->put(held_in_grid_);
  out->put(time_);
  out->put(steps_);
  out->put(time_origin_);
  out->put(steps_origin_);
  out->put(params_.step);  // the step the origin's count is of
}

void Simulation::restore(ByteReader* in, bool with_origin) {
  // Each value is checked as it is read, so that a state no simulation reaches (a bag's bytes
  // gone bad, or made by hand) is refused, naming it, rather than stepped into NaN or nonsense.
  const auto refuse = [](const std::string& why) {
    throw std::runtime_error("snapshot: the marble's " + why);
  };
  // Farther than any flight reaches (a marble at the fastest speed a step resolves would fly
  // for 1e144 s), and near enough that every square the step takes stays finite.
  const auto near = [](const Vec3& v) { return v.allFinite() && v.cwiseAbs().maxCoeff() <= 1e150; };
  Marble m;
  m.position = in->vec3();
  m.velocity = in->vec3();
  m.angular_velocity = in->vec3();
  if (!near(m.position)) refuse("position is not finite, or more than 1e150 m away");
  if (!m.velocity.allFinite()) refuse("velocity is not finite");
  if (!m.angular_velocity.allFinite()) refuse("angular velocity is not finite");
  const double w = in->get<double>(), x = in->get<double>(), y = in->get<double>(),
               z = in->get<double>();
  m.orientation = Quat(w, x, y, z);
  // (Each turn keeps it to unit length within rounding, some 1e-16.)
  if (!(std::abs(m.orientation.squaredNorm() - 1) <= 1e-9))
    refuse("orientation is not a unit quaternion (its squared norm is " +
           exactText(m.orientation.squaredNorm()) + ")");
  const auto phase = in->get<std::int32_t>();
  if (phase < static_cast<std::int32_t>(MarblePhase::Free) ||
      phase > static_cast<std::int32_t>(MarblePhase::OffBoard))
    refuse("phase " + std::to_string(phase) +
           " is none of free (0), in a hole (1), at the goal (2), off the board (3)");
  m.phase = static_cast<MarblePhase>(phase);
  // Beyond what a step resolves the physics is not answerable (a spin of 3e217 rad/s turned the
  // orientation to NaN). A session's own marble goes that fast only under extreme physics (100 g
  // over a 100 m fall, 0.1 s steps).
  const std::string too_fast = whyTooFast(m, params_);
  if (!too_fast.empty()) refuse(too_fast);
  m.contacts = in->get<std::int32_t>();
  if (m.contacts < 0) refuse("count of contacts is negative");
  Board board = board_;
  board.restore(in);
  const Vec3 held = in->vec3();
  if (!near(held))
    refuse("place on the board where it is held is not finite, or more than 1e150 m away");
  const double time = in->get<double>();
  if (!std::isfinite(time)) throw std::runtime_error("snapshot: the simulated time is not finite");
  // (No session has a time it could not restore: setParams and load refuse a step this refuses.)
  const std::string too_many = whyTooManySteps(time, params_.step);
  if (!too_many.empty()) throw std::runtime_error("snapshot: " + too_many);
  const auto steps = in->get<std::uint64_t>();
  // A state restored under the step it was saved with counts on from its origin, as the session
  // it was saved from does; under another step (a replay with other physics), or saved without
  // its origin, it counts its steps from where it was saved.
  double time_origin = time;
  std::uint64_t steps_origin = steps;
  if (with_origin) {
    const double saved_time_origin = in->get<double>();
    const auto saved_steps_origin = in->get<std::uint64_t>();
    const double saved_step = in->get<double>();
    if (saved_steps_origin > steps || !std::isfinite(saved_time_origin))
      throw std::runtime_error("snapshot: its time counts from a step it has not reached");
    if (!(std::isfinite(saved_step) && saved_step > 0))
      throw std::runtime_error("snapshot: the step its time counts in, " + exactText(saved_step) +
                               " s, is not a positive length");
    // The time is its origin's plus the steps since times the step, as step() works it out.
    const double counted =
        saved_time_origin + static_cast<double>(steps - saved_steps_origin) * saved_step;
    if (!(std::abs(time - counted) <= 1e-12 * std::abs(counted)))
      throw std::runtime_error("snapshot: the simulated time " + exactText(time) +
                               " s is not the time its steps count to (" + exactText(counted) +
                               " s)");
    if (saved_step == params_.step) {
      time_origin = saved_time_origin;
      steps_origin = saved_steps_origin;
    }
  }
  marble_ = m;
  board_ = board;
  held_in_grid_ = held;
  time_ = time;
  steps_ = steps;
  time_origin_ = time_origin;
  steps_origin_ = steps_origin;
  frame_ = gridFrame();
  board_work_ = 0;
  resting_ = false;
  events_.clear();
}

std::string Simulation::whyNotPlaceable(const Vec3& position_in_board) const {
  if (!position_in_board.allFinite()) return "not finite";
  const Vec3 grid = position_in_board + maze_.pivot();
  const Vec3 extent = maze_.extent();
  if (grid.x() < 0 || grid.y() < 0 || grid.x() > extent.x() || grid.y() > extent.y())
    return "off the board (outside its x-y extent)";
  // Wholly below the playing surface it would be off the board (or in a hole) at once; far above
  // it, a fall of minutes to the board, its rounding growing with the height.
  const double r = params_.marble_radius, above = grid.z() - maze_.floorTop();
  if (above < -r) return "below the board (its top under the floor's)";
  if (above > kMostPlacedHeight)
    return "more than " + exactText(kMostPlacedHeight) + " m above the board";
  GridFrame level;  // the board at rest, in its own frame
  level.grid_pivot = maze_.pivot();
  std::vector<Contact> touching;
  findContacts(maze_, level, position_in_board, params_.marble_radius, 0, &touching);
  for (const Contact& c : touching)
    if (c.depth > 1e-9) {
      std::ostringstream why;
      why << "inside tile (" << c.tile.x() << ", " << c.tile.y() << ", " << c.tile.z() << ") by "
          << c.depth << " m";
      return why.str();
    }
  return "";
}

GridFrame Simulation::gridFrame() const {
  GridFrame frame;
  frame.rotation = board_.rotation();
  frame.grid_pivot = maze_.pivot();  // the board's pivot, at the world's origin
  frame.angular_velocity = board_.angularVelocity();
  return frame;
}

Vec3 Simulation::startInBoard() const {
  if (params_.has_start_position) return params_.start_position;
  const Maze::Cell& s = maze_.start();
  return Vec3(maze_.axis(0).centre(s.i), maze_.axis(1).centre(s.j),
              maze_.floorTop() + params_.marble_radius) -
         maze_.pivot();
}

Vec3 Simulation::marbleInBoard() const {
  return frame_.toBoard(marble_.position);
}

void Simulation::reset() {
  board_.reset(params_.initial_roll, params_.initial_pitch);
  frame_ = gridFrame();
  placeMarble(startInBoard(), params_.start_velocity);
  events_.clear();
}

void Simulation::placeMarble(const Vec3& position_in_board, const Vec3& velocity,
                             const Vec3& angular_velocity) {
  marble_ = Marble();
  marble_.position = frame_.fromBoard(position_in_board);
  marble_.velocity = velocity;
  marble_.angular_velocity = angular_velocity;
  board_work_ = 0;
  resting_ = false;
}

double Simulation::energy() const {
  // Kinetic and potential energy are taken together at the instant the integrator's velocity
  // belongs to: semi-implicit Euler's is the velocity half a substep back, where the marble was
  // at p - v h/2. (With both taken now, a bounce would seem to gain m g h |v_z|.)
  const double m = mass_;
  const Vec3 position = marble_.position - integrator_->velocityLag() * substep_ * marble_.velocity;
  return 0.5 * m * marble_.velocity.squaredNorm() +
         0.5 * inertia_ * marble_.angular_velocity.squaredNorm() +
         m * params_.gravity * (position.z() + params_.board_position.z());
}

int Simulation::substepsFor() const {
  // A board that turns far in one step (a tilt snapping across its range) is taken in as many
  // more substeps as keep each turn within most_turn_, turning that much in each: the sweep
  // follows a substep's motion relative to the board as a chord, near its arc only for small
  // turns.
  int substeps = params_.substeps;
  // (A rate limit that keeps the turn small spares the probe.)
  if (!(params_.tilt_rate_limit > 0 && params_.tilt_rate_limit * params_.step <= most_turn_)) {
    Board probe = board_;
    probe.advance(params_.step);
    const double turn =
        std::max(std::abs(probe.roll() - board_.roll()), std::abs(probe.pitch() - board_.pitch()));
    if (turn > most_turn_ * substeps)
      substeps = static_cast<int>(std::min(10000.0, std::ceil(turn / most_turn_)));
  }
  // Air drag slows the marble at the rate k |v|: over a substep much longer than 1 / (k |v|) (a
  // light marble at speed, a long step) a scheme overshoots, turns the velocity round and makes it
  // grow without bound. The step is cut into as many more substeps as keep k |v| h within
  // kMostDragDecay, |v| bounded by the speed now and what gravity adds over the step.
  if (!forces_.constant()) {
    // (Gravity and drag alone never take the speed past the larger of the speed now and the
    // terminal speed, sqrt(g / k).)
    const double speed = marble_.velocity.norm();
    const double rate =
        forces_.drag() * std::min(speed + params_.gravity * params_.step,
                                  std::max(speed, std::sqrt(params_.gravity / forces_.drag())));
    if (rate * params_.step > kMostDragDecay * substeps)
      substeps =
          static_cast<int>(std::min(10000.0, std::ceil(rate * params_.step / kMostDragDecay)));
  }
  return substeps;
}

namespace {

/// Whether two marbles are the same to the last bit.
bool sameBits(const Marble& a, const Marble& b) {
  return a.phase == b.phase && a.contacts == b.contacts &&
         marble_maze::sameBits(a.position, b.position) &&
         marble_maze::sameBits(a.velocity, b.velocity) &&
         marble_maze::sameBits(a.angular_velocity, b.angular_velocity) &&
         marble_maze::sameBits(a.orientation, b.orientation);
}

}  // namespace

void Simulation::step() {
  events_.clear();
  if (!resting_) {
    // Only a board that did not turn in the last step can be left as it was: only then is the
    // step watched for a change (in play the board turns, and the step pays nothing for it).
    if (board_.angularVelocity() == Vec3::Zero())
      resting_ = substepsChangeNothing();
    else
      takeSubsteps();
  }
  ++steps_;
  time_ = time_origin_ + static_cast<double>(steps_ - steps_origin_) * params_.step;
}

void Simulation::takeSubsteps() {
  const int substeps = substepsFor();
  const double h = params_.step / substeps;
  substep_ = h;
  for (int i = 0; i < substeps; ++i) substep(h, time_ + i * h);
}

bool Simulation::substepsChangeNothing() {
  // A step is a function of the state (not of the time, which only stamps the events) and of
  // the inputs: one that changes nothing would change nothing again.
  const Marble before = marble_;
  const double roll = board_.roll(), pitch = board_.pitch();
  const Vec3 spin = board_.angularVelocity();
  takeSubsteps();
  return events_.empty() && sameBits(before, marble_) &&
         marble_maze::sameBits(roll, board_.roll()) &&
         marble_maze::sameBits(pitch, board_.pitch()) &&
         marble_maze::sameBits(spin, board_.angularVelocity());
}

void Simulation::substep(double h, double start_time) {
  ++counts_.substeps;
  BoardMotion motion = moveBoard(h);
  if (marble_.phase != MarblePhase::Free) {
    rideWithBoard();
    return;
  }
  gatherContacts(motion.start, h);
  // A contact struck at the start (a board kicking the marble) is an impulse before the
  // substep's forces act, so that the flight after it keeps the whole substep's gravity. The
  // kick answered the board's change of speed: the marble leaving after it leaves on its own, and
  // is not held as if it lagged the board's new motion.
  if (solver_.anyImpact(contacts_, marble_.velocity)) {
    impact(start_time);
    motion.previous_spin = motion.start.angular_velocity;
  }
  // A scheme that follows the turn takes a marble resting on one face of a turning board in the
  // board's frame, where the face stands in the pose of the start; otherwise the contacts push
  // along the middle's. (Against two contacts at once, a stick turning to slip on one of them
  // between stages makes the stages disagree: the substep is taken as a one-sample scheme
  // takes it.)
  const bool in_board_frame = contacts_.size() == 1 && !frame_.angular_velocity.isZero(0) &&
                              integrator_->followsTheTurn() && restsOnContacts();
  if (!in_board_frame) turnContactsToForcePose(motion, h);
  integrateToImpacts(h, start_time, motion, in_board_frame);
  turnMarble(h);
  checkFinish(start_time + h);
}

Simulation::BoardMotion Simulation::moveBoard(double h) {
  // The board's pose at the start of the substep, moving as it moves over the substep (its
  // motion in the last one kept apart).
  BoardMotion motion{frame_, frame_.angular_velocity, board_.roll(), board_.pitch()};
  board_.advance(h, most_turn_);
  frame_.rotation = board_.rotation();  // the pivot stays where it is in the grid
  frame_.angular_velocity = board_.angularVelocity();
  motion.start.angular_velocity = frame_.angular_velocity;
  return motion;
}

void Simulation::rideWithBoard() {
  marble_.position = frame_.toWorld(held_in_grid_);
  marble_.velocity = frame_.surfaceVelocity(marble_.position);
}

void Simulation::gatherContacts(const GridFrame& start, double h) {
  // Contacts against the board where it is at the start, moving as it moves over the substep;
  // and the tiles near enough for the substep's path to meet, about twice as far as it goes at
  // the marble's speed relative to the board (at most a radius, which bounds the lookup's cost).
  // (Its speed is bounded by the sum of its components' sizes, which takes no square root: a
  // skin only decides which tiles are looked at, never what the step finds.)
  const double goes = (marble_.velocity - start.surfaceVelocity(marble_.position)).lpNorm<1>() * h +
                      params_.gravity * h * h;
  near_.skin = std::min(params_.marble_radius, 2 * goes);
  near_.slack = kNearSlack * params_.marble_radius;
  findContacts(maze_, start, marble_.position, params_.marble_radius, kContactMargin, &contacts_,
               &near_);
  marble_.contacts = static_cast<int>(contacts_.size());
  pushOut();
}

void Simulation::turnContactsToForcePose(const BoardMotion& motion, double h) {
  // The contacts' forces act over the substep while the board turns: they push along its normals
  // in its pose at the instant the scheme's forces belong to: the middle of the substep (the
  // midpoint rule), or for a velocity half a substep behind its position (semi-implicit Euler's,
  // a leapfrog) the start. A rotation, not normals interpolated one by one: contacts at right
  // angles stay at right angles.
  const double at = 0.5 - integrator_->velocityLag();
  if (!(at > 0 && !contacts_.empty() && !frame_.angular_velocity.isZero(0))) return;
  const Mat3 pose =
      Board::rotationFor(motion.start_roll + at * (board_.roll() - motion.start_roll),
                         motion.start_pitch + at * (board_.pitch() - motion.start_pitch));
  // And they hold the velocity they leave at the substep's end to the surfaces as they move
  // then, as RATTLE holds velocity Verlet's: the marble's centre is carried to p + v h, where
  // the board moves at w x (p + v h), and the normal turns on over the rest of the substep by
  // w (1 - at) h, which a velocity v meets at (w x (p + v h) - v) x w (1 - at) h along the
  // middle's normal. (Held to the surfaces of the start, both schemes were first order on a
  // board turning at a constant rate, 30 to 370 times less accurate at 1 ms.) One shift for every
  // contact, from the surface's velocity where the marble's surface meets the normal in that
  // pose, as findContacts takes it: every contact asks one rigid motion of the marble.
  const Vec3& v = marble_.velocity;
  const Vec3& w = frame_.angular_velocity;
  const Vec3 end = marble_.position + v * h;
  const Vec3 ahead = cross(w, v * h) + ((1 - at) * h) * cross(cross(w, end) - v, w);
  for (Contact& c : contacts_) {
    c.normal = product(pose, c.grid_normal);  // (the pose was just put together)
    c.surface_velocity = startSurfaceVelocity(c) + ahead;
  }
}

void Simulation::turnMarble(double h) {
  if (params_.model == Model::Rolling && !marble_.angular_velocity.isZero(0))
    marble_.orientation = turnedBy(marble_.orientation, marble_.angular_velocity * h);
}

void Simulation::pushOut() {
  // Rounding can leave the marble overlapping a tile by a hair: move it out along the contact
  // normals, without touching its velocity.
  Vec3 moved = Vec3::Zero();
  for (const Contact& c : contacts_) {
    const double depth = c.depth - moved.dot(c.normal);
    if (depth <= 0) continue;
    marble_.position += depth * c.normal;
    moved += depth * c.normal;
  }
}

void Simulation::impact(double time) {
  Velocities b{marble_.velocity, marble_.angular_velocity};
  solver_.impact(contacts_, &b, &outcomes_);
  board_work_ += solver_.surfaceWork();
  marble_.velocity = b.linear;
  marble_.angular_velocity = b.angular;
  for (std::size_t i = 0; i < contacts_.size(); ++i)
    if (outcomes_[i].bounce)
      events_.push_back(
          {time, EventKind::Collision, contacts_[i].tile, outcomes_[i].approach_speed});
}

void Simulation::ContactDynamics::followTurn(const Vec3& start, const Vec3& spin) {
  turning_ = true;
  start_ = start;
  spin_ = spin;
  rate_ = spin.norm();
  axis_ = spin / rate_;
}

Velocities Simulation::ContactDynamics::after(const Velocities& start, double duration,
                                              const Sample& at) {
  if (turning_) return afterInBoardFrame(start, duration, at);
  Velocities b{start.linear + sim_->forces_.acceleration(start.linear) * duration, start.angular};
  if (sim_->acting().empty()) return b;  // in flight: nothing constrains it (and no work is done)
  // The first sample's outcomes say which contacts hold the marble; later ones are scratch.
  sim_->solver_.constrain(sim_->acting(), &b,
                          sampled_ ? &sim_->sample_outcomes_ : &sim_->acting_outcomes_);
  if (!sampled_) sim_->board_work_ += sim_->solver_.surfaceWork();
  sampled_ = true;
  return b;
}

Velocities Simulation::ContactDynamics::afterInBoardFrame(const Velocities& start, double duration,
                                                          const Sample& at) {
  // In the frame turning at w: gravity turned back by the board's turn since the start
  // (Rodrigues' formula), drag on the velocity through the air (the frame's velocity plus the
  // board's there), the Coriolis force -2 w x u and the centrifugal -w x (w x y). The spin
  // relative to the board turns back likewise: -w x s. (Only with contacts: see followTurn.)
  const Vec3& g = sim_->forces_.gravity();
  const double angle = rate_ * at.elapsed, c = std::cos(angle), s = std::sin(angle);
  const Vec3 gravity = c * g - s * cross(axis_, g) + ((1 - c) * axis_.dot(g)) * axis_;
  const Vec3 carried = cross(spin_, start_ + at.moved);  // the board's velocity there
  const Vec3 drag = sim_->forces_.acceleration(start.linear + carried) - g;
  const Vec3 a = gravity + drag - 2 * cross(spin_, start.linear) - cross(spin_, carried);
  const Velocities free{start.linear + a * duration,
                        start.angular - cross(spin_, start.angular) * duration};
  Velocities b = free;
  sim_->solver_.constrain(sim_->acting(), &b,
                          sampled_ ? &sim_->sample_outcomes_ : &sim_->acting_outcomes_);
  // Its surfaces stand still here: the work the board does through them is the contacts'
  // impulse on the marble against the board's motion there, J . (w x y) + L . w.
  if (!sampled_)
    sim_->board_work_ += sim_->mass_ * (b.linear - free.linear).dot(carried) +
                         sim_->inertia_ * (b.angular - free.angular).dot(spin_);
  sampled_ = true;
  return b;
}

void Simulation::chooseActingContacts(double duration, const Vec3& previous_spin) {
  // Most often all of them act, and are taken where they are; otherwise those that act are
  // copied apart.
  all_act_ = true;
  for (std::size_t i = 0; i < contacts_.size(); ++i) {
    const Contact& c = contacts_[i];
    const Vec3 relative = marble_.velocity - startSurfaceVelocity(c);
    // How much the marble's normal velocity relative to the surface under it changes over the
    // stretch while it moves with the board: it crosses to other points of the turning board,
    // |w| |v| h; the surface's normal turns under its relative velocity, |w| |v_rel| h, and its
    // point is carried round, |w|^2 |p| h; and the board's turn changed speed since the marble
    // last moved with it, |w - w_before| |p|. A departure slower than that is the lag of a
    // contact held at the stretch's start point and the board's last motion: the contact acts,
    // bringing the marble to the board's motion or letting it go.
    const double away = relative.dot(c.normal);
    const auto drift = [&] {
      const double w = frame_.angular_velocity.norm(),
                   p = (c.grid_point - frame_.grid_pivot).norm();  // from the pivot
      return w * (marble_.velocity.norm() + relative.norm() + w * p) * duration +
             (frame_.angular_velocity - previous_spin).norm() * p;
    };
    const bool leaving =
        integrator_->bends() && away > kRestingSpeed && away > kRestingSpeed + drift();
    if (leaving && all_act_) {
      some_acting_.assign(contacts_.begin(), contacts_.begin() + static_cast<std::ptrdiff_t>(i));
      all_act_ = false;
    } else if (!leaving && !all_act_) {
      some_acting_.push_back(c);
    }
  }
}

bool Simulation::restsOnContacts() const {
  // Neither approaching a contact nor leaving it faster than resting: the marble moves along the
  // board. (Where the board's change of speed since the last substep, or an impact, left it
  // moving across a contact, the substep is taken with the contacts of its middle, as by a
  // scheme that samples them once: the stages of one that samples them more often would take
  // up an approach only in part, RK4's leaving 3/8 of it.)
  for (const Contact& c : contacts_)
    if (std::abs((marble_.velocity - startSurfaceVelocity(c)).dot(c.normal)) > kRestingSpeed)
      return false;
  return true;
}

void Simulation::keepOutOfContacts(Trajectory* path, double duration, bool in_board_frame) const {
  // The path may not run into a tile the marble touches, whatever the velocities it was built
  // from said: it would end inside the tile. Its rate is linear in s, so a path that leaves
  // neither at its start nor at its end is clear of the tile all along.
  for (const Contact& c : acting()) {
    const Vec3& n = c.normal;
    const Vec3 surface = in_board_frame ? Vec3::Zero() : startSurfaceVelocity(c);
    const double start_into = (path->start_rate - surface).dot(n);
    if (start_into < 0) {
      path->first -= start_into * duration * n;
      path->velocity -= start_into * n;
      path->start_rate -= start_into * n;
      if (!path->curved) {  // the chord: its one rate is the end's too
        path->end.linear -= start_into * n;
        path->end_rate = path->start_rate;
        continue;
      }
      path->second += 0.5 * start_into * duration * n;  // the end's rate stays
    }
    if (!path->curved) continue;
    const double end_into = (path->end_rate - c.surface_velocity).dot(n);
    if (end_into < 0) {
      path->second -= 0.5 * end_into * duration * n;
      path->end.linear -= end_into * n;
      path->end_rate -= end_into * n;
    }
  }
  if (path->curved) path->velocity_change = path->end.linear - path->velocity;
}

void Simulation::keepOnHeldContacts(Sweep* sweep) const {
  // A contact that holds the marble leaves it no normal speed relative to the board, so it
  // stays on the surface: what the board's turning adds to the path across it (second order in
  // the step) would otherwise lift it off or sink it in by a few nanometres a step.
  const std::vector<Contact>& acting = this->acting();
  for (std::size_t i = 0; i < acting.size(); ++i) {
    if (!acting_outcomes_[i].holds()) continue;
    const Vec3& normal = acting[i].grid_normal;
    sweep->path -= sweep->path.dot(normal) * normal;
    sweep->bend -= sweep->bend.dot(normal) * normal;
    sweep->keepTo(normal, acting[i].grid_point);
  }
}

void Simulation::integrateToImpacts(double h, double start_time, const BoardMotion& motion,
                                    bool in_board_frame) {
  // The substep impact by impact: over what is left of it the field's forces and the contacts'
  // give the integrator's path, which is swept on the board for the first impact. The first
  // stretch is swept from where the marble was on the board at the start (the board then in its
  // start pose) to where it will be at the end, so that a board moving meanwhile is swept too;
  // after an impact the marble stands where the board carries it by the substep's end, and
  // moves on only as fast as it moves relative to the board.
  double done = 0;  // fraction of the substep
  for (int impacts = 0; impacts < kMaxImpactsPerSubstep; ++impacts) {
    const double rest = (1 - done) * h;
    // (After an impact the contacts are found in the end pose, and push along its normals over
    // what is left of the substep.)
    if (impacts == 0)
      chooseActingContacts(rest, motion.previous_spin);
    else
      chooseActingContacts(rest, frame_.angular_velocity);
    ContactDynamics dynamics(this);  // (its first sample says which contacts hold the marble)
    Velocities start{marble_.velocity, marble_.angular_velocity};
    // In the board's frame (the start's pose, turning with the board) the contacts stand still
    // and the marble moves relative to the board; its path there is its path on the board. (A
    // marble leaving every contact flies on the world's parabola, exactly.)
    const bool relative = in_board_frame && impacts == 0 && !acting().empty();
    if (relative) {
      const Vec3& w = frame_.angular_velocity;
      dynamics.followTurn(marble_.position, w);
      start = {start.linear - frame_.surfaceVelocity(marble_.position), start.angular - w};
      for (std::vector<Contact>* list : {&contacts_, &some_acting_})
        for (Contact& c : *list) c.surface_velocity.setZero();
      // It moves along them (restsOnContacts), exactly: its stages then agree on them.
      for (const Contact& c : acting()) start.linear -= start.linear.dot(c.normal) * c.normal;
    }
    Trajectory path = integrator_->advance(dynamics, start, Stretch{rest, h, impacts > 0});
    keepOutOfContacts(&path, rest, relative);
    Sweep sweep;
    sweep.radius = params_.marble_radius;
    sweep.margin = kContactMargin;
    sweep.resting_rate = kRestingSpeed * rest;
    // The path's bend in the grid frame, from the pose the path is taken in.
    sweep.bend = relative ? Vec3(motion.start.rotation.transpose() * path.second)
                          : Vec3(frame_.rotation.transpose() * path.second);
    if (relative) {
      const Mat3 to_grid = motion.start.rotation.transpose();
      sweep.from = motion.start.toGrid(marble_.position);
      sweep.path = to_grid * path.displacement() - sweep.bend;
      keepOnHeldContacts(&sweep);
      // Back to the world: the velocities relative to the board turned with it, plus its own.
      const Mat3 turn = frame_.rotation * to_grid;
      path.velocity = turn * path.velocity;
      path.velocity_change = turn * path.velocity_change;
      path.start_spin = turn * path.start_spin + frame_.angular_velocity;
      path.end.linear = turn * path.end.linear;
      path.end.angular = turn * path.end.angular + frame_.angular_velocity;
      // (The board's velocity where the marble ends is added below, once it is placed.)
    } else if (impacts == 0) {
      sweep.from = motion.start.toGrid(marble_.position);
      sweep.path = frame_.toGrid(marble_.position + path.displacement()) - sweep.from - sweep.bend;
      keepOnHeldContacts(&sweep);
    } else {
      const Vec3 carried = frame_.surfaceVelocity(marble_.position) * rest;
      sweep.from = frame_.toGrid(marble_.position);
      sweep.path = frame_.rotation.transpose() * (path.displacement() - carried) - sweep.bend;
    }
    // A path that cannot reach any tile near its start needs no walk of the grid. (After an
    // impact the marble touches the tile it met and keeps to no plane: the near tiles could not
    // clear its path.)
    SweepHit hit;
    const bool clear = impacts == 0 && sweep.clearOf(near_);
    const bool hits = !clear && timeOfImpact(maze_, frame_, sweep, &hit) == ImpactState::Hit;
    ++counts_.sweeps;
    counts_.sweeps_clear += clear;
    counts_.tiles_swept += hit.tiles_visited;
    if (!hits) {
      marble_.position = frame_.toWorld(sweep.at(1));
      marble_.velocity = path.end.linear;
      if (relative) marble_.velocity += frame_.surfaceVelocity(marble_.position);
      marble_.angular_velocity = path.end.angular;
      return;
    }
    Vec3 met = sweep.at(hit.fraction);
    if (impacts == 0 && acting().empty())  // a flight: its path is the world's parabola
      met = meetTurningFace(path, motion, hit.contact, &hit.fraction, met);
    marble_.position = frame_.toWorld(met);
    marble_.velocity = path.velocityAt(hit.fraction);
    if (relative) marble_.velocity += frame_.surfaceVelocity(marble_.position);
    marble_.angular_velocity = path.spinAt(hit.fraction);
    done += (1 - done) * hit.fraction;
    findContacts(maze_, frame_, marble_.position, params_.marble_radius, kContactMargin,
                 &contacts_);
    bool found = false;
    for (const Contact& c : contacts_) found = found || c.normal.dot(hit.contact.normal) > 1 - 1e-9;
    if (!found) contacts_.push_back(hit.contact);
    marble_.contacts = static_cast<int>(contacts_.size());
    impact(start_time + done * h);
    if (!(done < 1)) return;  // at the very end of the substep: nothing left to move
  }
  // A marble wedged in a corner meets a few impacts in one substep; beyond these it stays put.
}

Vec3 Simulation::meetTurningFace(const Trajectory& path, const BoardMotion& motion,
                                 const Contact& face, double* fraction, const Vec3& met) const {
  // The sweep follows the path relative to a turning board as a quadratic in s, off the true
  // one by some nanometres (the board's turn within the substep, second order): where it meets
  // a face, the instant is found again on the true path, the world's curve seen from the board
  // in its pose at s, by Newton's method (two or three steps from the sweep's instant).
  const Vec3& n = face.grid_normal;
  const bool is_face = (n.array() != 0).count() == 1;
  if (!is_face || frame_.angular_velocity.isZero(0)) return met;
  const double roll = motion.start_roll, pitch = motion.start_pitch;
  const double turn_roll = board_.roll() - roll, turn_pitch = board_.pitch() - pitch;
  const auto at = [&](double s) {
    const Mat3 pose = Board::rotationFor(roll + s * turn_roll, pitch + s * turn_pitch);
    return Vec3(pose.transpose() * (marble_.position + s * (path.first + s * path.second)) +
                frame_.grid_pivot);
  };
  const auto gap = [&](double s) { return n.dot(at(s) - face.grid_point) - params_.marble_radius; };
  double s = *fraction;
  constexpr double kDs = 1e-7;  // of the substep: the secant's width
  for (int i = 0; i < 3; ++i) {
    const double g = gap(s), slope = (gap(s + kDs) - gap(s - kDs)) / (2 * kDs);
    if (!(slope < 0)) return met;  // not approaching: the sweep's instant stands
    s -= g / slope;
  }
  if (!(std::abs(s - *fraction) < 1e-3 && s >= 0 && s <= 1)) return met;
  *fraction = s;
  return at(s);
}

void Simulation::checkFinish(double time) {
  const double r = params_.marble_radius;
  const double floor_top = maze_.floorTop();
  // Only a marble low enough to finish needs its column looked up: its height in the grid says
  // (as toGrid works it out), and whether it is finite: a coordinate that is not makes it not
  // finite, whatever the board's pose (0 times infinity is not a number).
  const double height = frame_.rotation.col(2).dot(marble_.position) + frame_.grid_pivot.z();
  const bool below = height < floor_top - r;  // wholly below the playing surface
  const bool at_goal_height = !maze_.goals().empty() && height < floor_top + 2 * r;
  const bool finite = std::isfinite(height);
  if (finite && !below && !at_goal_height) return;
  const Maze::Cell cell = maze_.cellAt(frame_.toGrid(marble_.position));
  const Index3 floor_tile(cell.i, cell.j, 0);
  if (!finite) {
    hold(MarblePhase::OffBoard, EventKind::OffBoard, floor_tile, time);
  } else if (below) {
    if (maze_.isHole(cell))
      hold(MarblePhase::InHole, EventKind::Hole, floor_tile, time);
    else
      hold(MarblePhase::OffBoard, EventKind::OffBoard, floor_tile, time);
  } else if (maze_.isGoal(cell)) {
    hold(MarblePhase::AtGoal, EventKind::Goal, floor_tile, time);
  }
}

void Simulation::hold(MarblePhase phase, EventKind kind, const Index3& tile, double time) {
  events_.push_back({time, kind, tile, marble_.velocity.norm()});
  marble_.phase = phase;
  if (!marble_.position.allFinite()) marble_.position = Vec3::Zero();  // the pivot
  if (!marble_.orientation.coeffs().allFinite()) marble_.orientation = Quat::Identity();
  held_in_grid_ = frame_.toGrid(marble_.position);
  marble_.velocity = frame_.surfaceVelocity(marble_.position);
  marble_.angular_velocity.setZero();
}

}  // namespace marble_maze
