// The tf frames of the chain world -> board -> marble (REP 105): their names, the defaults a
// namespace gives them, and the checks that keep the chain whole.
#pragma once

#include <tf2_msgs/TFMessage.h>

#include <string>

namespace marble_maze_ros {

struct Frames {
  std::string world = "world", board = "board", marble = "marble";
};

/// The default names for a node in namespace `ns`: the world shared, the board and the marble
/// under the namespace ("/" gives board, marble; "/a/b" gives a/b/board, a/b/marble), so that
/// nodes in two namespaces broadcast two boards and two marbles in one world.
Frames framesIn(const std::string& ns);

/// Why the frames do not make the chain, naming the parameter (world_frame, board_frame,
/// marble_frame): empty, starting with the '/' tf2 refuses, holding a space or a control
/// character, or named as another; "" when they do.
std::string whyNotAChain(const Frames& frames);

/// The first of `frames`' board and marble that `message` moves, "" when it moves neither.
std::string ownFrameIn(const tf2_msgs::TFMessage& message, const Frames& frames);

}  // namespace marble_maze_ros
