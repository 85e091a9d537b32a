#include "frames.h"

#include <algorithm>

#include "marble_maze/in_quotes.h"

namespace marble_maze_ros {

Frames framesIn(const std::string& ns) {
  const std::string prefix = ns.substr(std::min<std::size_t>(ns.find_first_not_of('/'), ns.size()));
  Frames frames;
  if (prefix.empty()) return frames;
  frames.board = prefix + "/board";
  frames.marble = prefix + "/marble";
  return frames;
}

std::string whyNotAChain(const Frames& frames) {
  const std::pair<const char*, const std::string*> named[] = {{"world_frame", &frames.world},
                                                              {"board_frame", &frames.board},
                                                              {"marble_frame", &frames.marble}};
  for (std::size_t i = 0; i < 3; ++i) {
    const std::string& frame = *named[i].second;
    const std::string key = named[i].first;
    if (frame.empty()) return key + ": a frame needs a name";
    if (frame[0] == '/')
      return key + ": " + marble_maze::inQuotes(frame) + " starts with '/', which tf2 refuses";
    // (RViz and tf's tools split names at spaces; a control character is never meant.)
    if (std::any_of(frame.begin(), frame.end(),
                    [](unsigned char c) { return c <= ' ' || c == 127; }))
      return key + ": " + marble_maze::inQuotes(frame) +
             " holds a space or a control character, which tf's tools cannot name";
    for (std::size_t j = 0; j < i; ++j)
      if (frame == *named[j].second)
        return key + ": " + marble_maze::inQuotes(frame) + " is " + named[j].first +
               " too; tf needs world -> board -> marble to be three frames";
  }
  return "";
}

std::string ownFrameIn(const tf2_msgs::TFMessage& message, const Frames& frames) {
  for (const geometry_msgs::TransformStamped& t : message.transforms)
    if (t.child_frame_id == frames.board || t.child_frame_id == frames.marble)
      return t.child_frame_id;
  return "";
}

}  // namespace marble_maze_ros
