#include "marble_maze/simulation.h"

#include <cmath>

namespace marble_maze {
namespace {

// Contacts are looked for this far beyond the marble's surface: far below anything visible, and
// above the gap that a turning board opens under a marble it carries in one step (its rotation,
// second order in the step: some nanometres), so that such a marble stays in contact instead of
// meeting the board anew every other step.
constexpr double kContactMargin = 1e-7;  // m
// A marble wedged in a corner meets a few impacts in one substep; beyond these it stays put.
constexpr int kMaxImpactsPerSubstep = 4;
constexpr double kPi = 3.14159265358979323846;

}  // namespace

Simulation::Simulation(const Scene& scene)
    : maze_(scene.maze), params_(scene.params), board_(params_), solver_(params_) {
  validate(params_);
  reset();
}

GridFrame Simulation::gridFrame() const {
  GridFrame frame;
  frame.rotation = board_.rotation();
  frame.pivot = Vec3::Zero();
  frame.origin = -(frame.rotation * maze_.pivot());
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
  return frame_.toGrid(marble_.position) - maze_.pivot();
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
  marble_.position = frame_.toWorld(position_in_board + maze_.pivot());
  marble_.velocity = velocity;
  marble_.angular_velocity = angular_velocity;
}

double Simulation::energy() const {
  // Semi-implicit Euler's velocity is the velocity half a substep back, where the marble was at
  // p - v h/2: kinetic and potential energy are taken together there. (With both taken now, a
  // bounce would seem to gain m g h |v_z|, which the scheme never does.)
  const double m = params_.marbleMass();
  const double h = params_.step / params_.substeps;
  const Vec3 position = marble_.position - 0.5 * h * marble_.velocity;
  return 0.5 * m * marble_.velocity.squaredNorm() +
         0.5 * params_.marbleInertia() * marble_.angular_velocity.squaredNorm() +
         m * params_.gravity * position.z();
}

void Simulation::step() {
  events_.clear();
  const double h = params_.step / params_.substeps;
  for (int i = 0; i < params_.substeps; ++i) substep(h, time() + i * h);
  ++steps_;
}

Vec3 Simulation::acceleration(const Vec3& velocity) const {
  Vec3 a(0, 0, -params_.gravity);
  if (params_.drag_coefficient > 0) {
    const double r = params_.marble_radius;
    const double area = kPi * r * r;
    a -= (0.5 * params_.air_density * params_.drag_coefficient * area * velocity.norm() /
          params_.marbleMass()) *
         velocity;
  }
  return a;
}

void Simulation::substep(double h, double start_time) {
  const GridFrame start = frame_;  // the board's pose at the start of the substep
  board_.advance(h);
  frame_ = gridFrame();
  if (marble_.phase != MarblePhase::Free) {  // a finished marble rides along with the board
    marble_.position = frame_.toWorld(held_in_grid_);
    marble_.velocity = frame_.surfaceVelocity(marble_.position);
    return;
  }
  // Contacts against the board where it is at the start, moving as it moves over the substep.
  GridFrame moving = start;
  moving.angular_velocity = frame_.angular_velocity;
  findContacts(maze_, moving, marble_.position, params_.marble_radius, kContactMargin, &contacts_);
  marble_.contacts = static_cast<int>(contacts_.size());
  pushOut();
  // Forces: semi-implicit Euler, the new velocity moves the marble.
  const Vec3 start_velocity = marble_.velocity;
  Vec3 change = acceleration(marble_.velocity) * h;
  marble_.velocity += change;
  // Impacts and their restitution are decided by the approach before this substep's forces, so
  // that gravity pressing a resting marble down is never bounced.
  respond(contacts_, start_velocity, start_time);
  takeUpHeldAcceleration(&change);
  move(h, start_time, start, change);
  if (params_.model == Model::Rolling) {
    const double angle = marble_.angular_velocity.norm() * h;
    if (angle > 0)
      marble_.orientation = (Quat(Eigen::AngleAxisd(angle, marble_.angular_velocity.normalized())) *
                             marble_.orientation)
                                .normalized();
  }
  checkFinish(start_time + h);
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

void Simulation::respond(const std::vector<Contact>& contacts, const Vec3& reference, double time) {
  MarbleBody body;
  body.velocity = marble_.velocity;
  body.angular_velocity = marble_.angular_velocity;
  body.mass = params_.marbleMass();
  body.inertia = params_.marbleInertia();
  body.radius = params_.marble_radius;
  solver_.solve(contacts, reference, &body, &outcomes_);
  marble_.velocity = body.velocity;
  marble_.angular_velocity = body.angular_velocity;
  for (std::size_t i = 0; i < contacts.size(); ++i)
    if (outcomes_[i].bounce)
      events_.push_back(
          {time, EventKind::Collision, contacts[i].tile, outcomes_[i].approach_speed});
}

void Simulation::takeUpHeldAcceleration(Vec3* change) const {
  // A contact that holds the marble (no bounce) takes up the acceleration into it for the rest
  // of the substep, as the floor does gravity.
  for (std::size_t i = 0; i < contacts_.size(); ++i) {
    const double into = change->dot(contacts_[i].normal);
    if (outcomes_[i].holds() && into < 0) *change -= into * contacts_[i].normal;
  }
}

Vec3 Simulation::keepOutOfContacts(Vec3* chord) const {
  // The straight path may not run into a tile the marble touches, whatever the parabola's
  // velocity at the impact said: a path into it would end inside the tile.
  Vec3 correction = Vec3::Zero();
  for (const Contact& c : contacts_) {
    const double into = (*chord + correction - c.surface_velocity).dot(c.normal);
    if (into < 0) correction -= into * c.normal;
  }
  *chord += correction;
  return correction;
}

void Simulation::keepOnHeldContacts(const GridFrame& start, Vec3* path) const {
  // A contact that holds the marble leaves it no normal speed relative to the board, so it
  // stays on the surface: what the board's turning adds to the path across it (second order in
  // the step) would otherwise lift it off or sink it in by a few nanometres a step.
  for (std::size_t i = 0; i < contacts_.size(); ++i) {
    if (!outcomes_[i].holds()) continue;
    const Vec3 normal = start.rotation.transpose() * contacts_[i].normal;
    *path -= path->dot(normal) * normal;
  }
}

void Simulation::move(double h, double start_time, const GridFrame& start, Vec3 change) {
  // Semi-implicit Euler moves the marble by h times its new velocity, which is its velocity at
  // mid-substep: over the substep it follows the parabola of the constant acceleration
  // change / h, so an impact at fraction s meets it at v + (s - 1/2) change. The path is swept
  // on the board, from where the marble was on it at the start (the board then in its start
  // pose) to where it will be at the end, so that a board moving meanwhile is swept too.
  Vec3 chord = marble_.velocity;  // mean velocity over what is left of the substep
  marble_.velocity += keepOutOfContacts(&chord);
  Vec3 from = start.toGrid(marble_.position);
  double s = 0;
  for (int impact = 0; impact < kMaxImpactsPerSubstep; ++impact) {
    // After an impact the marble stands where the board carries it by the substep's end; from
    // there it moves only as fast as it moves relative to the board.
    const Vec3 carried = s > 0 ? frame_.surfaceVelocity(marble_.position) : Vec3::Zero();
    const Vec3 to = marble_.position + (chord - carried) * ((1 - s) * h);
    Vec3 path = frame_.toGrid(to) - from;
    if (s == 0) keepOnHeldContacts(start, &path);
    SweepHit hit;
    if (!sweepSphereInGrid(maze_, frame_, from, path, params_.marble_radius, kContactMargin,
                           &hit)) {
      marble_.position = frame_.toWorld(from + path);
      return;
    }
    from += path * hit.fraction;
    marble_.position = frame_.toWorld(from);
    s += (1 - s) * hit.fraction;
    const Vec3 at_impact = marble_.velocity + (s - 0.5) * change;
    findContacts(maze_, frame_, marble_.position, params_.marble_radius, kContactMargin,
                 &contacts_);
    bool found = false;
    for (const Contact& c : contacts_) found = found || c.normal.dot(hit.contact.normal) > 1 - 1e-9;
    if (!found) contacts_.push_back(hit.contact);
    marble_.velocity = at_impact;
    respond(contacts_, at_impact, start_time + s * h);
    takeUpHeldAcceleration(&change);
    const Vec3 after = marble_.velocity;
    chord = after + (0.5 * (1 - s)) * change;
    marble_.velocity = after + (0.5 - s) * change + keepOutOfContacts(&chord);
  }
}

void Simulation::checkFinish(double time) {
  const Vec3 p = frame_.toGrid(marble_.position);
  const double r = params_.marble_radius;
  const Maze::Cell cell = maze_.cellAt(p);
  const Index3 floor_tile(cell.i, cell.j, 0);
  if (!marble_.position.allFinite()) {
    hold(MarblePhase::OffBoard, EventKind::OffBoard, floor_tile, time);
  } else if (p.z() < maze_.floorTop() - r) {  // wholly below the playing surface
    if (maze_.isHole(cell))
      hold(MarblePhase::InHole, EventKind::Hole, floor_tile, time);
    else
      hold(MarblePhase::OffBoard, EventKind::OffBoard, floor_tile, time);
  } else if (maze_.isGoal(cell) && p.z() < maze_.floorTop() + 2 * r) {
    hold(MarblePhase::AtGoal, EventKind::Goal, floor_tile, time);
  }
}

void Simulation::hold(MarblePhase phase, EventKind kind, const Index3& tile, double time) {
  events_.push_back({time, kind, tile, marble_.velocity.norm()});
  marble_.phase = phase;
  if (!marble_.position.allFinite()) marble_.position = frame_.toWorld(maze_.pivot());
  held_in_grid_ = frame_.toGrid(marble_.position);
  marble_.velocity = frame_.surfaceVelocity(marble_.position);
  marble_.angular_velocity.setZero();
}

}  // namespace marble_maze
