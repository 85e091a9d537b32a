// The maze: a 3-D grid of box tiles in the board frame, with its start, goals and holes.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "marble_maze/axis_slots.h"
#include "marble_maze/geometry.h"

namespace marble_maze {

/// A 3-D grid of solid or empty box tiles. Grid coordinates have their origin at the lower corner
/// of tile (0, 0, 0) and axes along the board's x (right), y (forward) and z (up). Layer k = 0 is
/// the floor slab; a cell whose floor tile is missing is a hole.
class Maze {
 public:
  Maze() = default;
  Maze(const AxisSlots& x, const AxisSlots& y, const AxisSlots& z);

  const AxisSlots& axis(int a) const { return axes_[a]; }
  const Index3& size() const { return size_; }
  bool contains(const Index3& t) const {
    return t.x() >= 0 && t.y() >= 0 && t.z() >= 0 && t.x() < size_.x() && t.y() < size_.y() &&
           t.z() < size_.z();
  }

  /// Whether tile t is solid; tiles outside the grid are empty.
  bool solid(const Index3& t) const { return contains(t) && (tiles_[offset(t)] & kSolid) != 0; }
  void setSolid(const Index3& t, bool solid);
  /// Whether the neighbour of tile t (inside the grid) across its face on `side` (-1 or +1) of
  /// `axis` is empty: a solid tile's face there is on the surface of the union of tiles. Kept
  /// with each tile, so that the contact and sweep tests look up no neighbour.
  bool faceOpen(const Index3& t, int axis, int side) const {
    return (tiles_[offset(t)] & faceBit(axis, side)) != 0;
  }

  /// The box of tile t in grid coordinates.
  Box tileBox(const Index3& t) const {
    return {{bounds_[0][t.x()], bounds_[1][t.y()], bounds_[2][t.z()]},
            {bounds_[0][t.x() + 1], bounds_[1][t.y() + 1], bounds_[2][t.z() + 1]}};
  }
  /// The whole grid's extent in grid coordinates.
  const Vec3& extent() const { return extent_; }
  /// The board's pivot in grid coordinates: the centre of the floor slab's top surface.
  const Vec3& pivot() const { return pivot_; }
  double floorTop() const { return axes_[2].upper(0); }

  /// Cells are (i, j) columns of the grid; a start, a goal or a hole is one column.
  struct Cell {
    int i = 0;
    int j = 0;
    bool operator==(const Cell& o) const { return i == o.i && j == o.j; }
  };
  const Cell& start() const { return start_; }
  void setStart(const Cell& c) { start_ = c; }
  const std::vector<Cell>& goals() const { return goals_; }
  void addGoal(const Cell& c) { goals_.push_back(c); }
  bool isGoal(const Cell& c) const;
  /// A hole is a column inside the grid whose floor tile (layer 0) is missing.
  bool isHole(const Cell& c) const;
  std::vector<Cell> holes() const;
  /// The column containing grid point p (unclamped).
  Cell cellAt(const Vec3& p) const { return {axes_[0].slotAt(p.x()), axes_[1].slotAt(p.y())}; }

  const std::string& name() const { return name_; }
  void setName(const std::string& name) { name_ = name; }

 private:
  // A tile's byte: whether it is solid, and for each of its faces whether the neighbour there
  // is empty.
  static constexpr std::uint8_t kSolid = 0x80;
  static constexpr std::uint8_t kAllFacesOpen = 0x3f;
  static std::uint8_t faceBit(int axis, int side) {
    return static_cast<std::uint8_t>(1u << (2 * axis + (side > 0 ? 1 : 0)));
  }
  std::size_t offset(const Index3& t) const {
    return (static_cast<std::size_t>(t.z()) * size_.y() + t.y()) * size_.x() + t.x();
  }

  std::array<AxisSlots, 3> axes_;
  Index3 size_ = Index3::Zero();
  Vec3 extent_ = Vec3::Zero();  // looked up on the hot path
  Vec3 pivot_ = Vec3::Zero();
  std::array<std::vector<double>, 3>
      bounds_;  // slot boundaries per axis, looked up on the hot path
  std::vector<std::uint8_t> tiles_;
  Cell start_;
  std::vector<Cell> goals_;
  std::string name_;
};

}  // namespace marble_maze
