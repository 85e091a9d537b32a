// The scenes of the step's benchmark (make bench), shared with the tests that bound what those
// scenes cost in counts (test_step_cost.cpp) and that use their mazes (test_collision.cpp).
#pragma once

#include <cstdlib>
#include <string>

#include "marble_maze/maze.h"

namespace marble_maze {
namespace bench {

/// An N x N cell maze of the classic game's proportions: outer walls, inner walls from a hash
/// of each wall's position relative to the centre, and a closed 4 x 4 cell room in the middle
/// where the marble runs. The room and its surroundings are the same in every size, so the
/// marble's path is too: only the size of the maze differs between the cases. Without `walls`
/// it is an open floor inside the outer walls.
inline Maze generatedMaze(int cells, bool walls = true) {
  const int n = 2 * cells + 1;
  const AxisSlots x(0.005, 0.0221, n), y(0.005, 0.02325, n), z(0.005, 0.012, 2);
  Maze maze(x, y, z);
  const int c = cells / 2 * 2 + 1;  // an odd (cell) slot near the centre
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      maze.setSolid({i, j, 0}, true);
      const bool post = i % 2 == 0 && j % 2 == 0;
      const bool wall_slot = (i % 2 == 0) != (j % 2 == 0);
      const bool outer = i == 0 || j == 0 || i == n - 1 || j == n - 1;
      const unsigned hash = static_cast<unsigned>(i - c) * 73856093u ^
                            static_cast<unsigned>(j - c) * 19349663u;  // wraps, as unsigned may
      const bool room_wall = (std::abs(i - c) == 5 && std::abs(j - c) <= 5) ||
                             (std::abs(j - c) == 5 && std::abs(i - c) <= 5);
      const bool inside_room = std::abs(i - c) < 5 && std::abs(j - c) < 5;
      const bool inner_wall = wall_slot && !inside_room && hash % 3 == 0;
      if (outer || (walls && (post || room_wall || inner_wall))) maze.setSolid({i, j, 1}, true);
    }
  maze.setStart({c, c});
  maze.setName(std::to_string(cells) + "x" + std::to_string(cells));
  return maze;
}

}  // namespace bench
}  // namespace marble_maze
