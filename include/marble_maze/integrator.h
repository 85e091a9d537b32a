// Time integration: how the marble's velocity and position advance over a stretch of time under
// the field's forces (gravity, air drag), and the path it takes there, along which impacts are
// looked for. The step owns contacts and impacts; a scheme is one small class here.
#pragma once

#include "marble_maze/geometry.h"
#include "marble_maze/params.h"

namespace marble_maze {

/// The field's forces on the marble per unit mass: gravity along -z of the world, and quadratic
/// air drag when it is switched on.
class FieldForces {
 public:
  explicit FieldForces(const Params& params);
  Vec3 acceleration(const Vec3& velocity) const;
  /// True when the acceleration is the same at every velocity (no drag).
  bool constant() const { return drag_ == 0; }

 private:
  Vec3 gravity_;
  double drag_;  // 1/m: the drag's acceleration is -drag |v| v
};

/// How velocity and position change over a stretch under the field's forces alone.
struct FreeMotion {
  Vec3 velocity_change = Vec3::Zero();
  Vec3 displacement = Vec3::Zero();
};

/// The marble's path over a stretch of time, s = 0 at its start and 1 at its end:
/// centre(s) = start + first s + second s^2, true velocity(s) = velocity + s velocity_change.
struct Trajectory {
  Vec3 first = Vec3::Zero();
  Vec3 second = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();
  Vec3 velocity_change = Vec3::Zero();
  Vec3 end_velocity = Vec3::Zero();  ///< the state's velocity after the stretch
  bool curved = true;  ///< impacts are looked for on the curve; false: on the chord (second = 0)

  Vec3 displacement() const { return first + second; }
  Vec3 velocityAt(double s) const { return velocity + s * velocity_change; }
};

/// What is left of a substep: from its start, or from an impact in it, to its end.
struct Stretch {
  double duration = 0;       ///< s
  double substep = 0;        ///< s, the whole substep
  bool from_impact = false;  ///< starts at an impact, where the velocity is the true one
};

/// A time integration scheme.
class Integrator {
 public:
  virtual ~Integrator() = default;
  /// The motion over `duration` under the field's forces alone, from the state's velocity.
  virtual FreeMotion freeMotion(const FieldForces& forces, const Vec3& velocity,
                                double duration) const = 0;
  /// The path over a stretch from the state's velocity at its start to `end_velocity`, the
  /// velocity after the contacts took their share, which acted as a constant force over the
  /// stretch; `free` is what freeMotion gave for it.
  virtual Trajectory trajectory(const Vec3& velocity, const Vec3& end_velocity,
                                const FreeMotion& free, const Stretch& stretch) const = 0;
  /// How far the state's velocity lies behind its position in time, in substeps.
  virtual double velocityLag() const { return 0; }
};

/// The scheme of that kind (schemes hold no state: one of each serves every simulation).
const Integrator& integratorFor(IntegratorKind kind);

}  // namespace marble_maze
