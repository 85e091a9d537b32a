#include "marble_maze/route_planner.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace marble_maze {
namespace {

constexpr double kRoom = 1.05;  // the free width a move needs, in marble diameters
constexpr double kDanger = 20;  // extra cost factor right next to a hole or an open edge
const int kSteps[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};

}  // namespace

RoutePlanner::RoutePlanner(const Maze& maze, double radius, double hole_margin)
    : maze_(maze), radius_(radius), hole_margin_(hole_margin) {
  // Where the marble can fall: holes, and open columns on the grid's rim (off the board).
  std::vector<Maze::Cell> drops = maze.holes();
  const int nx = maze.size().x(), ny = maze.size().y();
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      if ((i == 0 || j == 0 || i == nx - 1 || j == ny - 1) && open({i, j}))
        drops.push_back({i + (i == 0        ? -1
                              : i == nx - 1 ? 1
                                            : 0),
                         j + (j == 0        ? -1
                              : j == ny - 1 ? 1
                                            : 0)});
  danger_.assign(static_cast<std::size_t>(nx) * ny, 1.0);
  const double reach = hole_margin_ * radius_;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Vec2 c = centre({i, j});
      double nearest = std::numeric_limits<double>::infinity();
      for (const Maze::Cell& d : drops) {
        // Distance from the column's centre to the drop's square (slots outside the grid take
        // the width of the rim's slot).
        const auto span = [&](int a, int index, double* lo, double* hi) {
          const AxisSlots& axis = maze.axis(a);
          *lo = axis.lower(index) - maze.pivot()[a];
          *hi = axis.upper(index) - maze.pivot()[a];
        };
        double x0, x1, y0, y1;
        span(0, d.i, &x0, &x1);
        span(1, d.j, &y0, &y1);
        const double dx = std::max({x0 - c.x(), 0.0, c.x() - x1});
        const double dy = std::max({y0 - c.y(), 0.0, c.y() - y1});
        nearest = std::min(nearest, std::hypot(dx, dy));
      }
      danger_[static_cast<std::size_t>(j) * nx + i] =
          1 + kDanger * std::max(0.0, 1 - nearest / reach);
    }
}

bool RoutePlanner::open(const Maze::Cell& c) const {
  if (c.i < 0 || c.j < 0 || c.i >= maze_.size().x() || c.j >= maze_.size().y()) return false;
  if (!maze_.solid({c.i, c.j, 0})) return false;
  // Nothing in the layers the marble rolls through, up to its diameter above the floor.
  const AxisSlots& z = maze_.axis(2);
  for (int k = 1; k < maze_.size().z() && z.lower(k) < maze_.floorTop() + 2 * radius_; ++k)
    if (maze_.solid({c.i, c.j, k})) return false;
  return true;
}

Vec2 RoutePlanner::centre(const Maze::Cell& c) const {
  return Vec2(maze_.axis(0).centre(c.i), maze_.axis(1).centre(c.j)) - maze_.pivot().head<2>();
}

bool RoutePlanner::roomToMove(const Maze::Cell& c, int axis) const {
  // The free width across a move along `axis`: the run of open columns through c on the other.
  const int across = 1 - axis;
  double width = maze_.axis(across).width(across == 0 ? c.i : c.j);
  for (int side : {-1, 1}) {
    Maze::Cell n = c;
    for (;;) {
      (across == 0 ? n.i : n.j) += side;
      if (!open(n)) break;
      width += maze_.axis(across).width(across == 0 ? n.i : n.j);
    }
  }
  return width >= kRoom * 2 * radius_;
}

Maze::Cell RoutePlanner::columnAt(const Vec2& p) const {
  return maze_.cellAt(Vec3(p.x(), p.y(), 0) + maze_.pivot());
}

double RoutePlanner::danger(const Maze::Cell& c) const {
  return danger_[static_cast<std::size_t>(c.j) * maze_.size().x() + c.i];
}

Route RoutePlanner::plan(const Vec2& from) const {
  const int nx = maze_.size().x(), ny = maze_.size().y();
  const Maze::Cell first = columnAt(from);
  Route route;
  if (!open(first)) return route;
  const auto index = [nx](const Maze::Cell& c) { return static_cast<std::size_t>(c.j) * nx + c.i; };
  std::vector<double> cost(static_cast<std::size_t>(nx) * ny,
                           std::numeric_limits<double>::infinity());
  std::vector<int> previous(cost.size(), -1);
  // Dijkstra; ties broken by the column's index, so that the route never depends on anything
  // but the maze.
  using Entry = std::pair<double, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  cost[index(first)] = 0;
  queue.push({0, index(first)});
  int goal = -1;
  while (!queue.empty()) {
    const auto [c_cost, at] = queue.top();
    queue.pop();
    if (c_cost > cost[at]) continue;
    const Maze::Cell c{static_cast<int>(at % nx), static_cast<int>(at / nx)};
    if (maze_.isGoal(c)) {
      goal = static_cast<int>(at);
      break;
    }
    for (const auto& step : kSteps) {
      const Maze::Cell n{c.i + step[0], c.j + step[1]};
      const int axis = step[0] != 0 ? 0 : 1;
      if (!open(n) || !roomToMove(c, axis) || !roomToMove(n, axis)) continue;
      const double length = (centre(n) - centre(c)).norm();
      const double next = c_cost + length * danger(n);
      if (next < cost[index(n)]) {
        cost[index(n)] = next;
        previous[index(n)] = static_cast<int>(at);
        queue.push({next, index(n)});
      }
    }
  }
  if (goal < 0) return route;
  for (int at = goal; at >= 0; at = previous[static_cast<std::size_t>(at)])
    route.columns.push_back({at % nx, at / nx});
  std::reverse(route.columns.begin(), route.columns.end());
  for (const Maze::Cell& c : route.columns) route.waypoints.push_back(centre(c));
  return route;
}

}  // namespace marble_maze
