// The autopilot: plays the game as a person would, from what another node can see (the maze and
// the marble's position and velocity in the board frame), by tilting the board. It plans a route
// to a goal (RoutePlanner) and follows it with a velocity controller that slows before each turn.
// ROS-free, so that the ROS autopilot node, tests and the runner share it.
#pragma once

#include "marble_maze/route_planner.h"

namespace marble_maze {

struct AutopilotSettings {
  double tilt_limit = 0.17453292519943295;  ///< rad: the board's
  /// m/s^2 per unit sin(tilt) down the slope: (5/7) g for a rolling solid sphere, g sliding.
  double acceleration_per_tilt = 5.0 / 7.0 * 9.81;
  double max_speed = 0.1;       ///< m/s along the route
  double braking = 0.3;         ///< share of the largest acceleration used to slow before turns
  double response_time = 0.12;  ///< s: how fast the velocity error is corrected
  double hole_margin = 3.0;     ///< marble radii: keep this far from holes where there is room
  /// s: how long a new tilt takes to act on the marble (about the board's response time). The
  /// autopilot steers the marble from where it will be by then: steering it from where it was
  /// corrects too late, and with some 20 ms more of latency in the loop it overshoots, winds
  /// about its route or falls into a hole.
  double lead = 0.05;
};

/// Roll and pitch (rad) for the board.
struct Tilt {
  double roll = 0;
  double pitch = 0;
};

/// What the autopilot sees of the game: the marble's board-frame position and velocity, the
/// board's tilt, and how long ago they were measured (s): a message's age when it is read.
struct Observation {
  Vec2 position = Vec2::Zero();
  Vec2 velocity = Vec2::Zero();
  Tilt tilt;
  double age = 0;
};

class Autopilot {
 public:
  Autopilot(const Maze& maze, double marble_radius, const AutopilotSettings& settings);

  /// Steers on with other settings (the board's physics changed, the maze and marble did not):
  /// the route and the way along it stay.
  void setSettings(const AutopilotSettings& settings) { settings_ = settings; }

  /// Plans from the marble's board-frame position; false when no goal can be reached from there.
  bool plan(const Vec2& position);
  const Route& route() const { return route_; }
  /// The waypoint it steers for now.
  std::size_t next() const { return next_; }

  /// The tilt to aim the board at. The route is followed from where the marble was seen, and
  /// planned again when it has left it (a bounce into another column); the speed along it is
  /// controlled from where the marble will be when the tilt acts (`lead` plus the observation's
  /// age later, rolling down the board's slope as it is tilted now).
  Tilt steer(const Observation& seen);

 private:
  bool onRoute(const Vec2& position) const;
  double distanceToTurn(const Vec2& position) const;
  /// Whether `position` lies past waypoint k where the route runs straight through it, within a
  /// radius of the route's line.
  bool passedOnStraight(const Vec2& position, std::size_t k) const;
  /// The marble's board-frame acceleration down the slope of a board tilted so, walls aside.
  Vec2 accelerationAt(const Tilt& tilt) const;

  double radius_;
  AutopilotSettings settings_;
  RoutePlanner planner_;
  Route route_;
  std::size_t next_ = 0;
};

}  // namespace marble_maze
