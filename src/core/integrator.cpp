#include "marble_maze/integrator.h"

#include <cmath>

namespace marble_maze {
namespace {

/// The curve through the stretch with the start's velocity and the end's displacement, whose
/// rate at the end is `end_rate`; the velocity along it changes linearly from the start's to the
/// end's.
Trajectory curve(const Velocities& start, const Velocities& end, const Vec3& displacement,
                 const Vec3& end_rate, double duration) {
  Trajectory t;
  t.first = start.linear * duration;
  t.second = displacement - t.first;
  t.start_rate = start.linear;
  t.end_rate = end_rate;
  t.velocity = start.linear;
  t.velocity_change = end.linear - start.linear;
  t.start_spin = start.angular;
  t.end = end;
  return t;
}

Velocities plus(const Velocities& a, const Velocities& b, double scale) {
  return {a.linear + scale * b.linear, a.angular + scale * b.angular};
}

Velocities minus(const Velocities& a, const Velocities& b) {
  return {a.linear - b.linear, a.angular - b.angular};
}

/// x_{n+1} = x_n + h v_{n+1}: first order, the cheapest. For a constant acceleration its
/// velocity is the true one half a substep back, so it moves along the chord of the true
/// parabola, and the velocity at a point of the chord is taken from that parabola.
class SemiImplicitEuler : public Integrator {
 public:
  Trajectory advance(Dynamics& dynamics, const Velocities& start,
                     const Stretch& stretch) const override {
    const double h = stretch.duration;
    Trajectory t;
    t.curved = false;
    t.end = dynamics.after(start, h);
    t.start_spin = start.angular;
    t.velocity_change = t.end.linear - start.linear;
    // The true velocity at the start (the state's lags half a substep, except at an impact),
    // the chord's displacement, and the state's velocity at the end, again half a substep back.
    const double lag = stretch.from_impact ? 0 : 0.5 * stretch.substep;
    t.velocity = start.linear + (lag / h) * t.velocity_change;
    t.start_rate = t.end_rate = t.velocity + 0.5 * t.velocity_change;  // the chord's
    t.first = t.start_rate * h;
    t.end.linear = t.velocity + (1 - 0.5 * stretch.substep / h) * t.velocity_change;
    return t;
  }
  double velocityLag() const override { return 0.5; }
  bool bends() const override { return false; }
};

/// Second order, and exact under constant forces: x + v h + a h^2 / 2 with a the acceleration
/// of the field and the contacts together. A velocity-dependent force (drag) is averaged over
/// the stretch (Heun's trapezoid).
class VelocityVerlet : public Integrator {
 public:
  Trajectory advance(Dynamics& dynamics, const Velocities& start,
                     const Stretch& stretch) const override {
    const double h = stretch.duration;
    Velocities end = dynamics.after(start, h);
    if (!dynamics.constantForces()) {
      const Velocities again = dynamics.after(end, h, {start.linear * h, h});
      end = plus(start, plus(minus(end, start), minus(again, end), 1), 0.5);
    }
    // The displacement (v0 + v1) h / 2 from a start at v0 ends at v1.
    return curve(start, end, 0.5 * (start.linear + end.linear) * h, end.linear, h);
  }
};

/// Classical fourth-order Runge-Kutta on the constrained dynamics: each stage's acceleration is
/// what the field's forces and the contacts give together, so that drag on a rolling marble is
/// fourth order too, and so is a marble on a turning board, taken in the board's frame where the
/// frame's forces change along the stretch. Under constant forces one stage is exact: it is
/// velocity Verlet.
class RungeKutta4 : public Integrator {
 public:
  Trajectory advance(Dynamics& dynamics, const Velocities& start,
                     const Stretch& stretch) const override {
    const double h = stretch.duration;
    if (dynamics.constantForces()) return VelocityVerlet().advance(dynamics, start, stretch);
    // k_i: the velocity change over the whole stretch at stage i (h times the acceleration).
    const Velocities& v1 = start;
    const Velocities k1 = minus(dynamics.after(v1, h), v1);
    const Velocities v2 = plus(start, k1, 0.5);
    const Velocities k2 = minus(dynamics.after(v2, h, {v1.linear * (0.5 * h), 0.5 * h}), v2);
    const Velocities v3 = plus(start, k2, 0.5);
    const Velocities k3 = minus(dynamics.after(v3, h, {v2.linear * (0.5 * h), 0.5 * h}), v3);
    const Velocities v4 = plus(start, k3, 1);
    const Velocities k4 = minus(dynamics.after(v4, h, {v3.linear * h, h}), v4);
    Velocities end = start;
    for (const auto& [k, w] : {std::pair{k1, 1.0}, {k2, 2.0}, {k3, 2.0}, {k4, 1.0}})
      end = plus(end, k, w / 6);
    const Vec3 displacement = (v1.linear + 2 * v2.linear + 2 * v3.linear + v4.linear) * (h / 6);
    return curve(start, end, displacement, displacement * (2 / h) - start.linear, h);
  }
  bool followsTheTurn() const override { return true; }
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
