// Collision response: impulses at every contact at once. An approach faster than the bounce
// threshold is an impact and leaves at e times its speed, as eq. (1) says; a slower one is a
// resting or rolling contact and leaves at zero normal speed (no bounce, no sinking, no jitter).
// In the rolling model Coulomb friction acts at each contact point as well.
#pragma once

#include <vector>

#include "marble_maze/collision.h"
#include "marble_maze/params.h"

namespace marble_maze {

/// The marble as the solver sees it.
struct MarbleBody {
  Vec3 velocity = Vec3::Zero();
  Vec3 angular_velocity = Vec3::Zero();
  double mass = 1;
  double inertia = 1;
  double radius = 1;
};

/// What happened at one contact.
struct ContactOutcome {
  double approach_speed = 0;  ///< relative normal speed towards the tile before the response
  bool bounce = false;        ///< an impact (approach faster than the threshold)
  double normal_impulse = 0;  ///< N s

  /// The contact holds the marble on the tile (pressing, not bouncing off).
  bool holds() const { return !bounce && normal_impulse > 0; }
};

class ContactSolver {
 public:
  explicit ContactSolver(const Params& params) : params_(params) {}

  /// Changes body's velocities so that no contact approaches its tile. `reference` is the
  /// marble's velocity that decides impacts and their restitution (the velocity before this
  /// step's forces, or at the moment of an impact). `outcomes` gets one entry per contact.
  void solve(const std::vector<Contact>& contacts, const Vec3& reference, MarbleBody* body,
             std::vector<ContactOutcome>* outcomes);

 private:
  void iterate(const std::vector<Contact>& contacts, bool restitution, MarbleBody* body,
               std::vector<ContactOutcome>* outcomes);
  void resistRolling(const std::vector<Contact>& contacts,
                     const std::vector<ContactOutcome>& outcomes, MarbleBody* body) const;

  Params params_;
  std::vector<Vec3> friction_impulses_;  // reused: no allocation per step
};

}  // namespace marble_maze
