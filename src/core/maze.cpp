#include "marble_maze/maze.h"

#include <algorithm>

namespace marble_maze {

Maze::Maze(const AxisSlots& x, const AxisSlots& y, const AxisSlots& z)
    : axes_{x, y, z},
      size_(x.count(), y.count(), z.count()),
      extent_(x.length(), y.length(), z.length()),
      pivot_(extent_.x() / 2, extent_.y() / 2, z.upper(0)),
      tiles_(static_cast<std::size_t>(x.count()) * y.count() * z.count(), kAllFacesOpen) {
  for (int a = 0; a < 3; ++a)
    for (int k = 0; k <= size_[a]; ++k) bounds_[a].push_back(axes_[a].lower(k));
}

void Maze::setSolid(const Index3& t, bool solid) {
  std::uint8_t& tile = tiles_[offset(t)];
  tile = static_cast<std::uint8_t>(solid ? tile | kSolid : tile & ~kSolid);
  for (int a = 0; a < 3; ++a)
    for (int side : {-1, 1}) {
      Index3 n = t;
      n[a] += side;
      if (!contains(n)) continue;
      std::uint8_t& neighbour = tiles_[offset(n)];
      const std::uint8_t facing = faceBit(a, -side);  // the neighbour's face towards t
      neighbour = static_cast<std::uint8_t>(solid ? neighbour & ~facing : neighbour | facing);
    }
}

bool Maze::isGoal(const Cell& c) const {
  return std::find(goals_.begin(), goals_.end(), c) != goals_.end();
}

bool Maze::isHole(const Cell& c) const {
  return c.i >= 0 && c.j >= 0 && c.i < size().x() && c.j < size().y() && !solid({c.i, c.j, 0});
}

std::vector<Maze::Cell> Maze::holes() const {
  std::vector<Cell> result;
  for (int j = 0; j < size().y(); ++j)
    for (int i = 0; i < size().x(); ++i)
      if (isHole({i, j})) result.push_back({i, j});
  return result;
}

}  // namespace marble_maze
