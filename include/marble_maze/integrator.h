// Time integration: how the marble's velocities and position advance over a stretch of time, and
// the path it takes there, along which impacts are looked for. A scheme samples the marble's
// dynamics (the field's forces and the contacts' together, see Dynamics); the step owns contacts
// and impacts. A scheme is one small class here.
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
  const Vec3& gravity() const { return gravity_; }
  /// True when the acceleration is the same at every velocity (no drag).
  bool constant() const { return drag_ == 0; }
  /// 1/m: drag slows a marble at speed v at the rate drag() v (1/s).
  double drag() const { return drag_; }

 private:
  Vec3 gravity_;
  double drag_;  // 1/m: the drag's acceleration is -drag |v| v
};

/// Where and when in a stretch a scheme samples the dynamics: the marble moved by `moved` from
/// the stretch's start, `elapsed` seconds into it.
struct Sample {
  Vec3 moved = Vec3::Zero();
  double elapsed = 0;
};

/// The marble's dynamics as a scheme samples them: its velocities after `duration` from `start`
/// under the field's forces and the forces of the contacts it rests or rolls on (which keep it
/// out of their tiles, with friction and rolling resistance), as one first-order step gives
/// them, the forces taken where and when `at` says. Under constant forces, on contacts that
/// hold the marble all along, the change is linear in `duration`.
class Dynamics {
 public:
  virtual ~Dynamics() = default;
  virtual Velocities after(const Velocities& start, double duration, const Sample& at) = 0;
  Velocities after(const Velocities& start, double duration) {
    return after(start, duration, Sample());
  }
  /// True when the forces change neither with the velocity (no drag) nor along the stretch.
  virtual bool constantForces() const = 0;
};

/// What is left of a substep: from its start, or from an impact in it, to its end.
struct Stretch {
  double duration = 0;       ///< s
  double substep = 0;        ///< s, the whole substep
  bool from_impact = false;  ///< starts at an impact, where the velocity is the true one
};

/// The marble's path over a stretch, s = 0 at its start and 1 at its end:
/// centre(s) = start + first s + second s^2, true velocity(s) = velocity + s velocity_change;
/// the spin changes linearly from the start's to the end's.
struct Trajectory {
  Vec3 first = Vec3::Zero();
  Vec3 second = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();
  Vec3 velocity_change = Vec3::Zero();
  Vec3 start_spin = Vec3::Zero();
  /// m/s, how fast the centre moves at the start and the end: first / duration and
  /// (first + 2 second) / duration, as the scheme knows them rather than divided out again.
  Vec3 start_rate = Vec3::Zero();
  Vec3 end_rate = Vec3::Zero();
  Velocities end;      ///< the state's velocities after the stretch
  bool curved = true;  ///< impacts are looked for on the curve; false: on the chord (second = 0)

  Vec3 displacement() const { return first + second; }
  Vec3 velocityAt(double s) const { return velocity + s * velocity_change; }
  Vec3 spinAt(double s) const { return start_spin + s * (end.angular - start_spin); }
};

/// A time integration scheme.
class Integrator {
 public:
  virtual ~Integrator() = default;
  /// The path over a stretch from the state's velocities at its start.
  virtual Trajectory advance(Dynamics& dynamics, const Velocities& start,
                             const Stretch& stretch) const = 0;
  /// How far the state's velocity lies behind its position in time, in substeps.
  virtual double velocityLag() const { return 0; }
  /// Whether its paths bend (impacts found on the curve) or run straight (on the chord). A bent
  /// path can leave a tile and come back to it in one stretch; a straight one cannot.
  virtual bool bends() const { return true; }
  /// Whether it takes a marble resting on a face of a turning board in the board's frame, where
  /// the face stands still and the frame's forces change along the stretch (a scheme of several
  /// samples follows them to its order), rather than with the contacts of the substep's middle.
  virtual bool followsTheTurn() const { return false; }
};

/// The scheme of that kind (schemes hold no state: one of each serves every simulation).
const Integrator& integratorFor(IntegratorKind kind);

}  // namespace marble_maze
