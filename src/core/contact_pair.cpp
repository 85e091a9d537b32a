// Two contacts at right angles (the floor and a wall, the common case on a tile grid) solved
// directly: the Gauss-Seidel sweeps converge on them slowly, since each contact's friction pushes
// the marble along the other's normal. With the normal impulses eliminated (a contact's normal
// impulse answers its own approach and the other's friction along its normal), what is left is
// which contacts stick and which slip:
//   - both stick: a linear system in the frictions along the line where the surfaces meet, and
//     the frictions across it known up to a squeeze of the marble between the two surfaces,
//     which changes no velocity and is chosen inside both friction cones;
//   - one sticks, the other slips: one equation in one unknown (the slip's friction per unit of
//     slip), solved by Newton's method, which converges monotonically after its first step.
// The answer is taken only when every contact keeps to its law (presses, stays in its cone,
// slips against its friction); otherwise the sweeps solve the pair (both slipping, one leaving).
#include <cmath>

#include "marble_maze/contact_solver.h"

namespace marble_maze {

bool ContactSolver::solvePair(const std::vector<Contact>& contacts, double restitution,
                              Velocities* body, std::vector<ContactOutcome>* outcomes) {
  const Vec3& na = contacts[0].normal;
  const Vec3& nb = contacts[1].normal;
  if (std::abs(na.dot(nb)) > 1e-12) return false;
  const double m = constants_.mass, r = constants_.radius, mu = params_.friction;
  const double k = constants_.k;
  const double gamma = constants_.gamma;  // how a slip's friction along t turns its slip
  const double inv_m = constants_.inv_mass, inv_g = constants_.inv_g, inv_k = constants_.inv_k;
  // The normal velocity change each contact needs (its target less its approach), per unit mass.
  double need[2];
  for (int i = 0; i < 2; ++i)
    need[i] = normalNeed(contacts[i], (*outcomes)[i], restitution, body->linear);
  // In the frame of contact s and contact l (t = n_s x n_l along the line where they meet), the
  // slips the frictions f (f_s = fs_a n_l + fs_b t, f_l = fl_a n_s + fl_b t) leave are
  //   at s, across: A_s + g (fs_a - fl_a)      at s, along: Ws_t + k fs_b + fl_b / m
  //   at l, across: A_l - g (fs_a - fl_a)      at l, along: Wl_t + k fl_b + fs_b / m
  // with the normal impulses N_s = m need_s - fl_a, N_l = m need_l - fs_a.
  struct Frame {
    int s, l;
    Vec3 t;
    double A_s, A_l, ws_t, wl_t;
  };
  const auto frame = [&](int s, int l) {
    Frame f{s, l, contacts[s].normal.cross(contacts[l].normal), 0, 0, 0, 0};
    const Vec3& ns = contacts[s].normal;
    const Vec3& nl = contacts[l].normal;
    const Vec3 vs = body->linear - contacts[s].surface_velocity;
    const Vec3 vl = body->linear - contacts[l].surface_velocity;
    const Vec3& w = body->angular;
    f.A_s = vs.dot(nl) - r * w.dot(f.t) + need[l];
    f.A_l = vl.dot(ns) + r * w.dot(f.t) + need[s];
    f.ws_t = vs.dot(f.t) + r * w.dot(nl);
    f.wl_t = vl.dot(f.t) - r * w.dot(ns);
    return f;
  };
  const auto inCone = [&](double a, double b, double normal) {
    return normal > 0 && a * a + b * b <= mu * mu * normal * normal * (1 + 1e-9);
  };
  // Takes the frictions found in frame f: the impulses and velocities, when both press.
  const auto take = [&](const Frame& f, double fs_a, double fs_b, double fl_a, double fl_b) {
    const double Ns = m * need[f.s] - fl_a, Nl = m * need[f.l] - fs_a;
    if (!(Ns > 0 && Nl > 0)) return false;
    const Vec3& ns = contacts[f.s].normal;
    const Vec3& nl = contacts[f.l].normal;
    const Vec3 Fs = fs_a * nl + fs_b * f.t, Fl = fl_a * ns + fl_b * f.t;
    body->linear += (Ns * ns + Fs + Nl * nl + Fl) * inv_m;
    body->angular += ((-r * ns).cross(Fs) + (-r * nl).cross(Fl)) * constants_.inv_inertia;
    (*outcomes)[f.s].normal_impulse = Ns;
    (*outcomes)[f.l].normal_impulse = Nl;
    friction_impulses_[f.s] = Fs;
    friction_impulses_[f.l] = Fl;
    return true;
  };

  const Frame ab = frame(0, 1);
  const double d = -ab.A_s * inv_g;  // fs_a - fl_a when s sticks
  // Both stick: possible only when the two ask the same across (A_s + A_l = 0, as on a board
  // at rest); along, a 2 x 2 system; across, a squeeze fs_a = fl_a + d free within the cones.
  if (std::abs(ab.A_s + ab.A_l) < 1e-13) {
    const double inv_det = constants_.inv_stick_det;  // of the system k fs_b + fl_b / m = ...
    const double fs_b = (-ab.ws_t * k + ab.wl_t * inv_m) * inv_det;
    const double fl_b = (-ab.wl_t * k + ab.ws_t * inv_m) * inv_det;
    for (const double fl_a : {-0.5 * d, 0.0, -d}) {  // the least friction first
      const double fs_a = fl_a + d;
      if (inCone(fs_a, fs_b, m * need[0] - fl_a) && inCone(fl_a, fl_b, m * need[1] - fs_a))
        return take(ab, fs_a, fs_b, fl_a, fl_b);
    }
  }
  // One sticks (s), the other slips (l): the slip across is S = A_s + A_l whatever the
  // frictions, along it is beta + gamma fl_b, and the slip's friction is -lambda times its slip,
  // with lambda = mu N_l / |slip| and N_l = C + lambda S.
  for (const Frame& f : {ab, frame(1, 0)}) {
    const double ds = -f.A_s * inv_g;
    const double S = f.A_s + f.A_l;
    const double beta = f.wl_t - f.ws_t * constants_.inv_mk;
    const double C = m * need[f.l] - ds;
    const double plain = std::sqrt(S * S + beta * beta);  // the slip's size at lambda = 0
    if (!(C > 0 && plain - mu * S > 0)) continue;
    // phi(lambda) = lambda |slip(lambda)| - mu (C + lambda S) rises from -mu C through its root.
    // With S = 0 it is concave, and nearly so where S is small (as on a board, below): Newton's
    // method climbs to the root from below, and from above first steps below it once (the
    // tangent of a concave function lies above it). With q = 1 + lambda gamma and
    // R = sqrt(S^2 q^2 + beta^2) = q |slip|, its step phi / phi' is
    //   (lambda R^2 q - mu (C + lambda S) R q^2) / (R^2 q - lambda gamma beta^2 - mu S R q^2),
    // one square root and one division, the only waits on the iteration's path.
    // It starts from the root with S left out of |slip|, lambda |beta| = mu (C + lambda S) q, a
    // quadratic, mu S gamma lambda^2 - b lambda + mu C = 0, whose small term a = mu^2 gamma S C
    // is taken to first order: the root itself when S = 0, and within some (S q / beta)^2 of it
    // otherwise. A marble rolling along a wall has S at rounding's size (the two surfaces move
    // as one board: they ask the same motion across them), and the first step finds nothing
    // left to do: the answer waits on one division, where from the root with gamma = 0 it
    // waited on 2.6 steps on average. (That root, below phi's, is the start where the quadratic
    // has none.)
    const double b = std::abs(beta) - mu * S - mu * C * gamma, a = mu * mu * gamma * S * C;
    double lambda = mu * C * b / (b * b - a);
    if (!(b > 0 && b * b > 4 * a)) lambda = mu * C / (plain - mu * S);
    double last_step = 0;
    bool converged = false;
    ++pair_counts_.solves;
    for (int iteration = 0; iteration < 20 && !converged; ++iteration) {
      ++pair_counts_.newton_steps;
      const double q = 1 + lambda * gamma, R2 = S * S * q * q + beta * beta, R = std::sqrt(R2);
      const double slope = R2 * q - lambda * gamma * beta * beta - mu * S * R * q * q;
      if (!(slope > 0)) break;
      const double step = (lambda * R2 * q - mu * (C + lambda * S) * R * q * q) / slope;
      // A step within what rounding makes of it (phi's two terms cancel to some ulps of mu C,
      // which the slope, some |beta| / q^2, makes some ulps of lambda q) is no step: lambda is the
      // root as nearly as phi tells, and is kept, so that what follows need not wait for the
      // step's square root and division (the branch is foreseen).
      if (std::abs(step) <= 1e-15 * lambda * q) {
        converged = true;
        break;
      }
      const double next = lambda - step;
      // Newton's error squares each step (times phi'' / 2 phi', estimated from the last two
      // steps): done when what it leaves is below rounding, without a further step to see it.
      converged = std::abs(step) <= 1e-6 * next && last_step != 0 &&
                  std::abs(step * step * step) <= 1e-17 * next * last_step * last_step;
      last_step = step;
      lambda = next;
    }
    if (!(converged && lambda > 0)) continue;
    const double fl_a = -lambda * S, fl_b = -lambda * beta / (1 + lambda * gamma);
    const double fs_a = fl_a + ds, fs_b = -(f.ws_t + fl_b * inv_m) * inv_k;
    if (!inCone(fs_a, fs_b, m * need[f.s] - fl_a)) continue;
    if (take(f, fs_a, fs_b, fl_a, fl_b)) return true;
  }
  return false;
}

}  // namespace marble_maze
