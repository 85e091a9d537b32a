// What happens to the marble that a user or a learning agent wants to know.
#pragma once

#include <string>

#include "marble_maze/geometry.h"

namespace marble_maze {

enum class EventKind {
  Collision,  ///< an impact on a tile, faster than the bounce threshold
  Hole,       ///< fell into a hole
  Goal,       ///< reached a goal cell
  OffBoard,   ///< left the board other than through a hole
};

struct Event {
  double time = 0;  ///< s, simulation time
  EventKind kind = EventKind::Collision;
  Index3 tile = Index3::Zero();  ///< the tile hit, or the hole's or goal's floor tile (k = 0)
  double speed = 0;              ///< m/s, approach speed of an impact
};

/// "collision", "hole", "goal" or "off_board".
std::string toString(EventKind kind);

}  // namespace marble_maze
