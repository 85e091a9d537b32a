// A top-down picture of a maze, as a camera above the board sees it: for agents that learn from
// pixels, as CyberRunner's did.
#pragma once

#include <cstdint>
#include <vector>

#include "marble_maze/maze.h"

namespace marble_maze {

class Raster {
 public:
  /// The planes, in this order: walls (a solid tile above the floor), holes, goals, the marble.
  static constexpr int kChannels = 4;

  /// Square pixels of `pixel` metres over the whole grid; throws ParamError unless the pixel is
  /// in [0.0005, 0.1] m and the picture at most 4096 pixels a side.
  Raster(const Maze& maze, double pixel);
  int width() const { return width_; }
  int height() const { return height_; }
  /// Writes kChannels planes of height x width bytes, 255 where the thing is and 0 elsewhere,
  /// row 0 along the board's +y edge and column 0 along its -x edge (x to the right, y up, as
  /// seen from above), with a marble of `radius` at board-frame (x, y): the pixels whose centres
  /// it covers, and always the pixel its centre is in.
  void draw(double x, double y, double radius, std::uint8_t* out) const;

 private:
  double pixel_ = 0;
  int width_ = 0, height_ = 0;
  Vec3 pivot_;
  std::vector<std::uint8_t> still_;  // the three planes that do not move
};

}  // namespace marble_maze
