// Route planning over a maze's columns: from the marble to a goal, around walls and holes, only
// where the marble has room. Knows the maze and the marble's size, nothing of the physics.
#pragma once

#include <vector>

#include "marble_maze/maze.h"

namespace marble_maze {

using Vec2 = Eigen::Vector2d;

/// A route: waypoints in the board frame's x-y plane (m), from the marble's column to a goal's
/// centre. Empty when no goal can be reached.
struct Route {
  std::vector<Vec2> waypoints;
  std::vector<Maze::Cell> columns;  ///< the columns the waypoints are the centres of
  bool found() const { return !waypoints.empty(); }
};

class RoutePlanner {
 public:
  /// `radius`: the marble's. Columns closer than `hole_margin` times the radius to a hole or an
  /// open edge of the board cost more to cross, so the route keeps away from them where it can.
  RoutePlanner(const Maze& maze, double radius, double hole_margin = 3.0);

  /// The cheapest route from the column under `from` (board frame) to any goal: a search over the
  /// columns that have a floor and nothing above it, moving to a neighbour only where the free
  /// width across the move leaves room for the marble.
  Route plan(const Vec2& from) const;

  /// Whether a column can hold the marble: a floor under it, no tile where the marble rolls.
  bool open(const Maze::Cell& c) const;
  /// The board-frame centre of a column.
  Vec2 centre(const Maze::Cell& c) const;
  /// The column under a board-frame point.
  Maze::Cell columnAt(const Vec2& p) const;

 private:
  bool roomToMove(const Maze::Cell& c, int axis) const;
  double danger(const Maze::Cell& c) const;

  Maze maze_;
  double radius_;
  double hole_margin_;
  std::vector<double> danger_;  // per column: extra cost factor near holes and open edges
};

}  // namespace marble_maze
