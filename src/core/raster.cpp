#include "marble_maze/raster.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "marble_maze/params.h"

namespace marble_maze {

Raster::Raster(const Maze& maze, double pixel) : pixel_(pixel), pivot_(maze.pivot()) {
  if (!(pixel >= 0.0005 && pixel <= 0.1))
    throw ParamError("raster pixel: " + exactText(pixel) + " m is out of range [0.0005, 0.1]");
  const double w = std::ceil(maze.extent().x() / pixel), h = std::ceil(maze.extent().y() / pixel);
  if (w > 4096 || h > 4096)
    throw ParamError("raster pixel: " + exactText(pixel) + " m makes a picture of " + exactText(w) +
                     " x " + exactText(h) + " pixels, more than 4096 a side");
  width_ = static_cast<int>(w);
  height_ = static_cast<int>(h);
  const std::size_t plane = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  still_.assign(3 * plane, 0);
  for (int r = 0; r < height_; ++r)
    for (int c = 0; c < width_; ++c) {
      const Vec3 at((c + 0.5) * pixel, maze.extent().y() - (r + 0.5) * pixel, 0);
      const Maze::Cell cell = maze.cellAt(at);
      bool wall = false;
      for (int k = 1; k < maze.size().z(); ++k) wall = wall || maze.solid({cell.i, cell.j, k});
      const std::size_t p = static_cast<std::size_t>(r) * static_cast<std::size_t>(width_) +
                            static_cast<std::size_t>(c);
      still_[p] = wall ? 255 : 0;
      still_[plane + p] = maze.isHole(cell) ? 255 : 0;
      still_[2 * plane + p] = maze.isGoal(cell) ? 255 : 0;
    }
}

void Raster::draw(double x, double y, double radius, std::uint8_t* out) const {
  const std::size_t plane = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  std::memcpy(out, still_.data(), still_.size());
  std::uint8_t* marble = out + 3 * plane;
  std::memset(marble, 0, plane);
  if (!std::isfinite(x) || !std::isfinite(y)) return;
  // The marble in the picture's pixels (column, row from the top), fractional.
  const double col = (x + pivot_.x()) / pixel_;
  const double row = static_cast<double>(height_) - (y + pivot_.y()) / pixel_;
  const double reach = radius / pixel_;
  const auto clampTo = [](double v, int n) {
    return static_cast<int>(std::clamp(v, 0.0, static_cast<double>(n)));
  };
  for (int r = clampTo(std::floor(row - reach), height_); r < clampTo(row + reach + 1, height_);
       ++r)
    for (int c = clampTo(std::floor(col - reach), width_); c < clampTo(col + reach + 1, width_);
         ++c) {
      const double dc = c + 0.5 - col, dr = r + 0.5 - row;
      const bool centre =
          c == static_cast<int>(std::floor(col)) && r == static_cast<int>(std::floor(row));
      if (centre || dc * dc + dr * dr <= reach * reach)
        marble[static_cast<std::size_t>(r) * static_cast<std::size_t>(width_) +
               static_cast<std::size_t>(c)] = 255;
    }
}

}  // namespace marble_maze
