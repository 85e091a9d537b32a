#include "marble_maze/integrator.h"

#include <cmath>

namespace marble_maze {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// x_{n+1} = x_n + h v_{n+1}: first order, the cheapest. Its velocity is the exact one half a
/// substep back (for a constant acceleration), so it moves along the chord of the parabola, and
/// the velocity at a point of the chord is taken from that parabola.
class SemiImplicitEuler : public Integrator {
 public:
  FreeMotion freeMotion(const FieldForces& forces, const Vec3& velocity,
                        double duration) const override {
    FreeMotion m;
    m.velocity_change = forces.acceleration(velocity) * duration;
    m.displacement = (velocity + m.velocity_change) * duration;
    return m;
  }
  Trajectory trajectory(const Vec3& velocity, const Vec3& end_velocity, const FreeMotion&,
                        const Stretch& stretch) const override {
    // With the constant acceleration of the velocity's change over the stretch: the true
    // velocity at its start (the state's lags half a substep, except at an impact), the chord's
    // displacement, and the state's velocity at its end, again half a substep back.
    const double h = stretch.duration;
    Trajectory t;
    t.curved = false;
    t.velocity_change = end_velocity - velocity;
    const double lag = stretch.from_impact ? 0 : 0.5 * stretch.substep;
    t.velocity = velocity + (lag / h) * t.velocity_change;
    t.first = (t.velocity + 0.5 * t.velocity_change) * h;
    t.end_velocity = t.velocity + (1 - 0.5 * stretch.substep / h) * t.velocity_change;
    return t;
  }
  double velocityLag() const override { return 0.5; }
};

/// Schemes whose velocity belongs to the state's instant and whose path is the curve of their
/// free motion plus the contacts' constant force: exact wherever the forces are constant.
class CurveIntegrator : public Integrator {
 public:
  Trajectory trajectory(const Vec3& velocity, const Vec3& end_velocity, const FreeMotion& free,
                        const Stretch& stretch) const override {
    const double duration = stretch.duration;
    Trajectory t;
    const Vec3 by_contacts = end_velocity - velocity - free.velocity_change;
    t.first = velocity * duration;
    t.second = free.displacement + 0.5 * duration * by_contacts - t.first;
    t.velocity = velocity;
    t.velocity_change = end_velocity - velocity;
    t.end_velocity = end_velocity;
    return t;
  }
};

/// Second order, and exact under a constant acceleration: x + v h + a h^2 / 2. A velocity-
/// dependent force (drag) is averaged over the stretch (Heun).
class VelocityVerlet : public CurveIntegrator {
 public:
  FreeMotion freeMotion(const FieldForces& forces, const Vec3& velocity,
                        double duration) const override {
    Vec3 a = forces.acceleration(velocity);
    if (!forces.constant()) a = 0.5 * (a + forces.acceleration(velocity + a * duration));
    FreeMotion m;
    m.velocity_change = a * duration;
    m.displacement = (velocity + 0.5 * m.velocity_change) * duration;
    return m;
  }
};

/// Classical fourth-order Runge-Kutta on (x, v): for forces that change over the stretch.
/// Under a constant acceleration it is the exact parabola, as velocity Verlet.
class RungeKutta4 : public CurveIntegrator {
 public:
  FreeMotion freeMotion(const FieldForces& forces, const Vec3& velocity,
                        double duration) const override {
    const double h = duration;
    FreeMotion m;
    if (forces.constant()) {
      m.velocity_change = forces.acceleration(velocity) * h;
      m.displacement = (velocity + 0.5 * m.velocity_change) * h;
      return m;
    }
    const Vec3 v1 = velocity, a1 = forces.acceleration(v1);
    const Vec3 v2 = velocity + 0.5 * h * a1, a2 = forces.acceleration(v2);
    const Vec3 v3 = velocity + 0.5 * h * a2, a3 = forces.acceleration(v3);
    const Vec3 v4 = velocity + h * a3, a4 = forces.acceleration(v4);
    m.velocity_change = h / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
    m.displacement = h / 6 * (v1 + 2 * v2 + 2 * v3 + v4);
    return m;
  }
};

}  // namespace

FieldForces::FieldForces(const Params& params)
    : gravity_(0, 0, -params.gravity),
      drag_(params.drag_coefficient > 0
                ? 0.5 * params.air_density * params.drag_coefficient * kPi * params.marble_radius *
                      params.marble_radius / params.marbleMass()
                : 0) {}

Vec3 FieldForces::acceleration(const Vec3& velocity) const {
  if (drag_ == 0) return gravity_;
  return gravity_ - drag_ * velocity.norm() * velocity;
}

const Integrator& integratorFor(IntegratorKind kind) {
  static const SemiImplicitEuler semi_implicit_euler;
  static const VelocityVerlet velocity_verlet;
  static const RungeKutta4 rk4;
  switch (kind) {
    case IntegratorKind::SemiImplicitEuler:
      return semi_implicit_euler;
    case IntegratorKind::RungeKutta4:
      return rk4;
    case IntegratorKind::VelocityVerlet:
      break;
  }
  return velocity_verlet;
}

}  // namespace marble_maze
