#include "marble_maze/events.h"

namespace marble_maze {

std::string toString(EventKind kind) {
  switch (kind) {
    case EventKind::Collision:
      return "collision";
    case EventKind::Hole:
      return "hole";
    case EventKind::Goal:
      return "goal";
    case EventKind::OffBoard:
      return "off_board";
  }
  return "unknown";
}

}  // namespace marble_maze
