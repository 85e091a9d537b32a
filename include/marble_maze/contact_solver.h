// Collision response: impulses at every contact at once. An approach faster than the bounce
// threshold is an impact and leaves at e times its speed, as eq. (1) says; a slower one is a
// resting or rolling contact and leaves at zero normal speed (no bounce, no sinking, no jitter).
// In the rolling model Coulomb friction acts at each contact point as well.
#pragma once

#include <cstdint>
#include <vector>

#include "marble_maze/collision.h"
#include "marble_maze/params.h"

namespace marble_maze {

/// What happened at one contact.
struct ContactOutcome {
  double approach_speed = 0;  ///< relative normal speed towards the tile before the response
  bool bounce = false;        ///< an impact (approach faster than the threshold)
  double normal_impulse = 0;  ///< N s

  /// The contact holds the marble on the tile (pressing, not bouncing off).
  bool holds() const { return !bounce && normal_impulse > 0; }
};

/// How often the pair solver went to Newton's method, and the steps it took there: a count, the
/// same on every machine, that make bench shows and a test bounds (a marble rolling along a
/// wall takes one step a solve).
struct PairSolveCounts {
  std::uint64_t solves = 0;
  std::uint64_t newton_steps = 0;
  PairSolveCounts& operator+=(const PairSolveCounts& other) {
    solves += other.solves;
    newton_steps += other.newton_steps;
    return *this;
  }
};

class ContactSolver {
 public:
  explicit ContactSolver(const Params& params);

  /// Whether a contact is approached faster than the bounce threshold: an impact.
  bool anyImpact(const std::vector<Contact>& contacts, const Vec3& velocity) const;
  /// An impact, at an instant: an approach faster than the bounce threshold leaves at e times
  /// its speed (eq. (1)), a slower one at zero; friction acts with it. `outcomes` gets one entry
  /// per contact.
  void impact(const std::vector<Contact>& contacts, Velocities* body,
              std::vector<ContactOutcome>* outcomes);
  /// The contacts' forces over a stretch of time, given body's velocity at its end as the field's
  /// forces alone would leave it: no contact is approached at the end (none bounces), friction
  /// acts within its cone, rolling resistance slows the spin.
  void constrain(const std::vector<Contact>& contacts, Velocities* body,
                 std::vector<ContactOutcome>* outcomes);
  /// The work (J) the moving surfaces did on the marble in the last impact or constrain: the sum
  /// of each contact's impulse dotted with its surface's velocity (0 on a board at rest). The
  /// marble's energy gain from a solve is at most this.
  double surfaceWork() const { return surface_work_; }
  const PairSolveCounts& pairCounts() const { return pair_counts_; }

 private:
  void iterate(const std::vector<Contact>& contacts, double restitution, Velocities* body,
               std::vector<ContactOutcome>* outcomes);
  /// The normal speed a contact leaves at (eq. (1)): `restitution` times its approach when it
  /// bounces, else 0 (it rests or rolls on the tile).
  double leavingSpeed(const ContactOutcome& o, double restitution) const {
    return o.bounce ? restitution * o.approach_speed : 0;
  }
  /// The change of the marble's normal speed a contact asks for: its leaving speed less the
  /// normal speed of `velocity` relative to the contact's surface.
  double normalNeed(const Contact& c, const ContactOutcome& o, double restitution,
                    const Vec3& velocity) const {
    return leavingSpeed(o, restitution) - (velocity - c.surface_velocity).dot(c.normal);
  }
  /// Two contacts at right angles, solved directly (contact_pair.cpp) when one or both stick:
  /// true with body, outcomes and frictions set; false, changing nothing, otherwise.
  bool solvePair(const std::vector<Contact>& contacts, double restitution, Velocities* body,
                 std::vector<ContactOutcome>* outcomes);
  /// Three contacts at right angles (a corner), solved directly (contact_triple.cpp) when all
  /// three stick: true with body, outcomes and frictions set; false, changing nothing, otherwise.
  bool solveTriple(const std::vector<Contact>& contacts, double restitution, Velocities* body,
                   std::vector<ContactOutcome>* outcomes);
  /// constrain() for one contact, as iterate() and measureWork() work it out, to the bit.
  void constrainOne(const Contact& c, Velocities* body, ContactOutcome* outcome);
  void resistRolling(const std::vector<Contact>& contacts, Velocities* body) const;
  void measureWork(const std::vector<Contact>& contacts,
                   const std::vector<ContactOutcome>& outcomes);

  /// The marble's constants as the solves use them, worked out once: each solve would otherwise
  /// begin by waiting on a chain of divisions.
  struct MarbleConstants {
    double mass, inertia, radius;
    double inv_mass, inv_inertia;
    double g;  ///< r^2 / I: how a tangential impulse at the surface turns the spin
    double k;  ///< 1/m + g: the tangential compliance at the surface
    /// The effective mass for a tangential impulse there, 1 / (1/m + r^2 / I): k's reciprocal,
    /// but worked out from the inverses as the sweeps always took it (which rounds otherwise).
    double tangent_mass;
    double gamma;  ///< k - 1 / (m^2 k): how a pair's slipping friction turns its slip
    /// 1 / g, 1 / k, 1 / (m k) and 1 / (k^2 - 1/m^2), for the pair's solve: a product by a
    /// reciprocal where a quotient would wait some 14 cycles on its path to the answer.
    double inv_g, inv_k, inv_mk, inv_stick_det;
  };

  Params params_;
  double bounce_threshold_;  // params_'s, worked out once
  MarbleConstants constants_;
  std::vector<Vec3> friction_impulses_;  // reused: no allocation per step
  double surface_work_ = 0;
  PairSolveCounts pair_counts_;
};

}  // namespace marble_maze
