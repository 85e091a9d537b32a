#include "marble_maze/autopilot.h"

#include <algorithm>
#include <cmath>

namespace marble_maze {
namespace {

// An observation older than this (s) is predicted from as if it were this old: a stalled message
// is not extrapolated into nonsense.
constexpr double kLongestAge = 0.25;

}  // namespace

Autopilot::Autopilot(const Maze& maze, double marble_radius, const AutopilotSettings& settings)
    : radius_(marble_radius),
      settings_(settings),
      planner_(maze, marble_radius, settings.hole_margin) {}

bool Autopilot::plan(const Vec2& position) {
  route_ = planner_.plan(position);
  next_ = route_.waypoints.size() > 1 ? 1 : 0;
  return route_.found();
}

bool Autopilot::onRoute(const Vec2& position) const {
  // On the route while in a column between the last waypoint reached and the next two.
  const Maze::Cell here = planner_.columnAt(position);
  const std::size_t from = next_ > 1 ? next_ - 2 : 0;
  const std::size_t to = std::min(route_.columns.size(), next_ + 2);
  for (std::size_t k = from; k < to; ++k)
    if (route_.columns[k] == here) return true;
  return false;
}

double Autopilot::distanceToTurn(const Vec2& position) const {
  // Along the route from the marble to the next waypoint where the route turns, or to its end.
  const auto& w = route_.waypoints;
  double distance = (w[next_] - position).norm();
  for (std::size_t k = next_; k + 1 < w.size(); ++k) {
    const Vec2 in = k > 0 ? (w[k] - w[k - 1]).normalized() : Vec2((w[k] - position).normalized());
    const Vec2 out = (w[k + 1] - w[k]).normalized();
    if (in.dot(out) < 0.99) break;  // w[k] is a turn
    distance += (w[k + 1] - w[k]).norm();
  }
  return distance;
}

bool Autopilot::passedOnStraight(const Vec2& position, std::size_t k) const {
  const auto& w = route_.waypoints;
  if (k == 0 || k + 1 >= w.size()) return false;
  const Vec2 in = (w[k] - w[k - 1]).normalized(), out = (w[k + 1] - w[k]).normalized();
  if (in.dot(out) < 0.99) return false;  // a turn: the marble must brake for it, not pass it
  const Vec2 from = position - w[k];
  return from.dot(out) > 0 && std::abs(from.x() * out.y() - from.y() * out.x()) < radius_;
}

Vec2 Autopilot::accelerationAt(const Tilt& tilt) const {
  // a = k sin(tilt) down the slope: positive pitch lowers +x, positive roll raises +y.
  const double k = settings_.acceleration_per_tilt;
  return Vec2(k * std::sin(tilt.pitch), -k * std::sin(tilt.roll));
}

Tilt Autopilot::steer(const Observation& seen) {
  const Vec2& position = seen.position;
  if (!route_.found() || !onRoute(position)) {
    if (!plan(position)) return Tilt();
  }
  const auto& w = route_.waypoints;
  // Where the marble will be, and how fast, when the tilt acts.
  const double ahead = settings_.lead + std::clamp(seen.age, 0.0, kLongestAge);
  const Vec2 slope = accelerationAt(seen.tilt);
  const Vec2 then = position + ahead * (seen.velocity + 0.5 * ahead * slope);
  const Vec2 velocity = seen.velocity + ahead * slope;
  // A waypoint is reached when the marble is within a radius of it, now or by then, or will be
  // past it where the route runs straight on (else it would be steered back to it); the next two
  // are looked at too, in case the marble passed one on the way.
  const double reach = radius_;
  for (std::size_t k = next_; k < std::min(w.size(), next_ + 3); ++k)
    if ((w[k] - position).norm() < reach || (w[k] - then).norm() < reach ||
        passedOnStraight(then, k))
      next_ = std::min(k + 1, w.size() - 1);

  const double largest = settings_.acceleration_per_tilt * std::sin(settings_.tilt_limit);
  // As fast as allows stopping at the next turn (or the goal) with the braking share.
  const double brake = settings_.braking * largest;
  const double speed = std::min(settings_.max_speed, std::sqrt(2 * brake * distanceToTurn(then)));
  const Vec2 to = w[next_] - then;
  const Vec2 wanted = to.norm() > 0 ? Vec2(speed * to.normalized()) : Vec2::Zero();
  Vec2 accel = (wanted - velocity) / settings_.response_time;
  // The tilt that gives that acceleration (accelerationAt's inverse).
  const auto angle = [&](double a) {
    return std::asin(std::clamp(a / settings_.acceleration_per_tilt, -1.0, 1.0));
  };
  Tilt tilt;
  tilt.pitch = std::clamp(angle(accel.x()), -settings_.tilt_limit, settings_.tilt_limit);
  tilt.roll = std::clamp(-angle(accel.y()), -settings_.tilt_limit, settings_.tilt_limit);
  return tilt;
}

}  // namespace marble_maze
