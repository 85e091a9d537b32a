#include "marble_maze/contact_solver.h"

#include <algorithm>
#include <cmath>

namespace marble_maze {
namespace {

// Gauss-Seidel sweeps over the contacts. One contact is solved exactly by one sweep (and
// constrained by constrainOne, that sweep's operations without its bookkeeping), two at right
// angles directly (solvePair) when one of them sticks, three at right angles (solveTriple) when
// all stick; the sweeps settle the rest (edges, two contacts both slipping, a corner the marble
// slides in), converging by a factor of 0.15 to 0.4 a sweep.
constexpr int kMaxIterations = 8;
// A velocity change below this (m/s) is rounding: the sweeps have converged.
constexpr double kConverged = 1e-12;
// Halvings of the restitution that simultaneous impacts may leave at without adding energy:
// within 1e-9 of it.
constexpr int kRestitutionBisections = 30;

/// n copies of `value` in v, reusing its storage: assign() without its out-of-line call, which
/// costs more than the copies (this runs several times a step).
template <typename T>
void fill(std::vector<T>* v, std::size_t n, const T& value) {
  v->resize(n);
  std::fill(v->begin(), v->end(), value);
}

/// Kinetic energy relative to the mean velocity of the touched surfaces.
double relativeEnergy(const std::vector<Contact>& contacts, const Vec3& velocity,
                      const Velocities& body, double mass, double inertia) {
  Vec3 surface = Vec3::Zero();
  for (const Contact& c : contacts) surface += c.surface_velocity;
  surface /= static_cast<double>(contacts.size());
  return 0.5 * mass * (velocity - surface).squaredNorm() +
         0.5 * inertia * body.angular.squaredNorm();
}

}  // namespace

ContactSolver::ContactSolver(const Params& params)
    : params_(params), bounce_threshold_(params.bounceThreshold()) {
  MarbleConstants& m = constants_;
  m.mass = params.marbleMass();
  m.inertia = params.marbleInertia();
  m.radius = params.marble_radius;
  m.inv_mass = 1.0 / m.mass;
  m.inv_inertia = 1.0 / m.inertia;
  m.g = m.radius * m.radius / m.inertia;
  m.k = 1 / m.mass + m.g;
  m.tangent_mass = 1.0 / (m.inv_mass + m.radius * m.radius * m.inv_inertia);
  m.gamma = m.k - 1 / (m.mass * m.mass * m.k);
  m.inv_g = 1 / m.g;
  m.inv_k = 1 / m.k;
  m.inv_mk = 1 / (m.mass * m.k);
  m.inv_stick_det = 1 / (m.k * m.k - m.inv_mass * m.inv_mass);
}

bool ContactSolver::anyImpact(const std::vector<Contact>& contacts, const Vec3& velocity) const {
  for (const Contact& c : contacts)
    if (-(velocity - c.surface_velocity).dot(c.normal) > bounce_threshold_) return true;
  return false;
}

void ContactSolver::impact(const std::vector<Contact>& contacts, Velocities* body,
                           std::vector<ContactOutcome>* outcomes) {
  fill(outcomes, contacts.size(), ContactOutcome());
  surface_work_ = 0;
  if (contacts.empty()) return;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    const double approach = -(body->linear - c.surface_velocity).dot(c.normal);
    (*outcomes)[i].approach_speed = approach;
    (*outcomes)[i].bounce = approach > bounce_threshold_;
  }
  const Velocities before = *body;
  iterate(contacts, params_.restitution, body, outcomes);
  // Newton's restitution at several simultaneous impacts can add energy (walls at an acute angle;
  // a floor and a wall struck at once with friction, whose impulses turn the marble's spin up);
  // where it would, the impacts leave at the largest restitution that does not, so that the
  // response stays continuous in e. A perfectly inelastic impact never adds energy: bisection
  // keeps a restitution that does not (the low end) and closes on one that would.
  const double m = constants_.mass, I = constants_.inertia;
  const double energy = relativeEnergy(contacts, before.linear, before, m, I) * (1 + 1e-12);
  const auto gains = [&] { return relativeEnergy(contacts, body->linear, *body, m, I) > energy; };
  if (contacts.size() > 1 && params_.restitution > 0 && gains()) {
    *body = before;
    iterate(contacts, 0, body, outcomes);
    // (On a turning board, where the energy is taken relative to the surfaces' mean motion, an
    // inelastic impact may seem to gain too: then it is the answer.)
    if (!gains()) {
      double keeps = 0, adds = params_.restitution;
      for (int k = 0; k < kRestitutionBisections; ++k) {
        const double e = 0.5 * (keeps + adds);
        *body = before;
        iterate(contacts, e, body, outcomes);
        (gains() ? adds : keeps) = e;
      }
      *body = before;
      iterate(contacts, keeps, body, outcomes);
    }
  }
  measureWork(contacts, *outcomes);
}

void ContactSolver::constrain(const std::vector<Contact>& contacts, Velocities* body,
                              std::vector<ContactOutcome>* outcomes) {
  fill(outcomes, contacts.size(), ContactOutcome());
  surface_work_ = 0;
  if (contacts.empty()) return;
  // Rolling resistance first, so that friction turns its torque into the marble's slowing in the
  // same stretch: a constant resistance then slows it at a constant rate, exactly.
  if (params_.model == Model::Rolling && params_.rolling_resistance > 0)
    resistRolling(contacts, body);
  if (contacts.size() == 1) {  // a marble rolling on a floor: most steps
    constrainOne(contacts[0], body, &(*outcomes)[0]);
    return;
  }
  iterate(contacts, 0, body, outcomes);
  measureWork(contacts, *outcomes);
}

void ContactSolver::constrainOne(const Contact& c, Velocities* body, ContactOutcome* o) {
  // One sweep of iterate() over one contact that does not bounce, its frictions starting at
  // zero, and measureWork(), each operation as they do it (so bit for bit the same), without
  // the sweeps' bookkeeping: the vectors of impulses, the loops and the test for convergence.
  Vec3 velocity = body->linear, spin = body->angular;
  const Vec3& n = c.normal;
  const double impulse =
      std::max(0.0, 0.0 + (0.0 - (velocity - c.surface_velocity).dot(n)) * constants_.mass);
  o->normal_impulse = impulse;
  Vec3 friction = Vec3::Zero();
  if (params_.model == Model::Rolling && params_.friction > 0) {
    const Vec3 arm = -constants_.radius * n;
    const Vec3 slip = velocity + spin.cross(arm) - c.surface_velocity;  // (before the impulse)
    const Vec3 tangential_slip = slip - slip.dot(n) * n;
    friction = Vec3::Zero() - tangential_slip * constants_.tangent_mass;
    const double limit = params_.friction * impulse;
    const double size2 = friction.squaredNorm();
    if (size2 > limit * limit) friction *= limit / std::sqrt(size2);
    velocity += impulse * constants_.inv_mass * n;
    velocity += friction * constants_.inv_mass;
    spin += arm.cross(friction) * constants_.inv_inertia;
  } else {
    velocity += impulse * constants_.inv_mass * n;
  }
  body->linear = velocity;
  body->angular = spin;
  surface_work_ = 0.0 + (impulse * n + friction).dot(c.surface_velocity);
}

void ContactSolver::measureWork(const std::vector<Contact>& contacts,
                                const std::vector<ContactOutcome>& outcomes) {
  surface_work_ = 0;
  for (std::size_t i = 0; i < contacts.size(); ++i)
    surface_work_ += (outcomes[i].normal_impulse * contacts[i].normal + friction_impulses_[i])
                         .dot(contacts[i].surface_velocity);
}

void ContactSolver::iterate(const std::vector<Contact>& contacts, double restitution,
                            Velocities* body, std::vector<ContactOutcome>* outcomes) {
  const bool rolling = params_.model == Model::Rolling && params_.friction > 0;
  fill(&friction_impulses_, contacts.size(), Vec3(Vec3::Zero()));
  for (auto& o : *outcomes) o.normal_impulse = 0;
  if (rolling && contacts.size() == 2 && solvePair(contacts, restitution, body, outcomes)) return;
  if (rolling && contacts.size() == 3 && solveTriple(contacts, restitution, body, outcomes)) return;
  const double inv_mass = constants_.inv_mass;
  const double inv_inertia = constants_.inv_inertia;
  const double r = constants_.radius;
  const double tangent_mass = constants_.tangent_mass;
  // The velocities are worked on in locals, not through `body`: stores and loads of them in
  // memory, in pieces that do not match, would make each sweep wait.
  Vec3 velocity = body->linear, spin = body->angular;
  const double mass = constants_.mass;
  const int iterations = contacts.size() == 1 ? 1 : kMaxIterations;
  for (int iteration = 0; iteration < iterations; ++iteration) {
    double largest_change2 = 0;  // the square of any impulse's change in this sweep, (N s)^2
    for (std::size_t i = 0; i < contacts.size(); ++i) {
      const Contact& c = contacts[i];
      ContactOutcome& o = (*outcomes)[i];
      // Eq. (1): the normal part of the velocity relative to the board's surface leaves at
      // e times its approach speed; resting contacts leave at zero.
      const double impulse =
          std::max(0.0, o.normal_impulse + normalNeed(c, o, restitution, velocity) * mass);
      const double normal_change = impulse - o.normal_impulse;
      // The slip at the contact point is taken before the normal impulse changes the velocity:
      // it changes it only along the normal, which the slip's tangential part leaves out, and
      // so the friction need not wait for the impulse.
      const Vec3 arm = -r * c.normal;
      const Vec3 slip = velocity + spin.cross(arm) - c.surface_velocity;
      velocity += normal_change * inv_mass * c.normal;
      largest_change2 = std::max(largest_change2, normal_change * normal_change);
      o.normal_impulse = impulse;
      if (!rolling) continue;
      // Coulomb friction at the contact point: stop slipping, within mu times the normal impulse.
      const Vec3 tangential_slip = slip - slip.dot(c.normal) * c.normal;
      Vec3 total = friction_impulses_[i] - tangential_slip * tangent_mass;
      const double limit = params_.friction * impulse;
      const double size2 = total.squaredNorm();
      if (size2 > limit * limit) total *= limit / std::sqrt(size2);
      const Vec3 change = total - friction_impulses_[i];
      friction_impulses_[i] = total;
      velocity += change * inv_mass;
      spin += arm.cross(change) * inv_inertia;
      largest_change2 = std::max(largest_change2, change.squaredNorm());
    }
    // Converged: a further sweep would change no velocity by more than 1e-12 m/s.
    if (largest_change2 * inv_mass * inv_mass < kConverged * kConverged) break;
  }
  body->linear = velocity;
  body->angular = spin;
}

void ContactSolver::resistRolling(const std::vector<Contact>& contacts, Velocities* body) const {
  // A torque of c_rr N r against the rolling part of the spin, with N the impulse that stops the
  // contact's approach (exact for one contact; the contacts of a tile grid are at right angles).
  for (const Contact& c : contacts) {
    const Vec3& n = c.normal;
    const double normal_impulse =
        std::max(0.0, -(body->linear - c.surface_velocity).dot(n)) * constants_.mass;
    const Vec3 rolling_spin = body->angular - body->angular.dot(n) * n;
    const double spin = rolling_spin.norm();
    if (spin == 0 || normal_impulse == 0) continue;
    const double change =
        params_.rolling_resistance * normal_impulse * constants_.radius / constants_.inertia;
    body->angular -= rolling_spin * (std::min(spin, change) / spin);
  }
}

}  // namespace marble_maze
