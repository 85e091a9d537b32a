// Three contacts at right angles (the floor and two walls: a corner, where a tilted board wedges
// the marble) solved directly when all three stick, as they do while the marble is held in the
// corner: the Gauss-Seidel sweeps converge on them slowly, each contact's friction pushing the
// marble along the other two's normals.
//
// In the frame of the normals, contact i's friction has a part a_ij along each other normal n_j.
// A normal impulse answers its own contact's approach less the others' frictions along its
// normal, N_i = m need_i - sum_j a_ji, which fixes the marble's velocity along every normal
// whatever the frictions. What is left of the slip at i along n_j then depends on the frictions
// only through the spin they give, and only through a_ij - a_ji:
//   s_ij = W_ij + g (a_ij - a_ji),   W_ij = (v - u_i) . n_j + need_j - r w . (n_i x n_j),
// with g = r^2 / I. All three stick when each pair's difference stops both of its slips,
// a_ij - a_ji = -W_ij / g = W_ji / g: possible only when W_ij + W_ji = 0. That holds, to
// rounding, when no contact bounces and the contacts' surface velocities are the board's rigid
// motion where the marble's surface meets each normal (as findContacts takes them), on a board
// at rest or turning. The mean of
// each pair, a squeeze of the marble between two surfaces, changes no velocity: the least
// friction (zero means) is taken, and the answer is kept only when every normal impulse presses
// and every friction lies in its cone; otherwise the sweeps solve the three.
#include <cmath>

#include "marble_maze/contact_solver.h"

namespace marble_maze {

bool ContactSolver::solveTriple(const std::vector<Contact>& contacts, double restitution,
                                Velocities* body, std::vector<ContactOutcome>* outcomes) {
  for (int i = 0; i < 3; ++i)
    if (std::abs(contacts[i].normal.dot(contacts[(i + 1) % 3].normal)) > 1e-12) return false;
  const double m = constants_.mass, r = constants_.radius, mu = params_.friction;
  const double g = constants_.g;
  const Vec3& w = body->angular;
  double need[3];
  for (int i = 0; i < 3; ++i)
    need[i] = normalNeed(contacts[i], (*outcomes)[i], restitution, body->linear);
  const auto W = [&](int i, int j) {
    const Vec3& ni = contacts[i].normal;
    const Vec3& nj = contacts[j].normal;
    return (body->linear - contacts[i].surface_velocity).dot(nj) + need[j] -
           r * w.dot(ni.cross(nj));
  };
  double a[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};  // a[i][j]: friction at i along n_j
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const double w_ij = W(i, j), w_ji = W(j, i);
    if (std::abs(w_ij + w_ji) > 1e-13) return false;
    a[i][j] = -0.5 * w_ij / g;
    a[j][i] = 0.5 * w_ij / g;
  }
  double normal[3];
  for (int i = 0; i < 3; ++i) {
    normal[i] = m * need[i];
    for (int j = 0; j < 3; ++j)
      if (j != i) normal[i] -= a[j][i];
    double friction2 = 0;
    for (int j = 0; j < 3; ++j) friction2 += a[i][j] * a[i][j];
    if (!(normal[i] > 0 && friction2 <= mu * mu * normal[i] * normal[i] * (1 + 1e-9))) return false;
  }
  Vec3 impulse = Vec3::Zero(), angular = Vec3::Zero();
  for (int i = 0; i < 3; ++i) {
    const Vec3& ni = contacts[i].normal;
    Vec3 friction = Vec3::Zero();
    for (int j = 0; j < 3; ++j)
      if (j != i) friction += a[i][j] * contacts[j].normal;
    impulse += normal[i] * ni + friction;
    angular += (-r * ni).cross(friction);
    (*outcomes)[i].normal_impulse = normal[i];
    friction_impulses_[i] = friction;
  }
  body->linear += impulse / m;
  body->angular += angular / constants_.inertia;
  return true;
}

}  // namespace marble_maze
