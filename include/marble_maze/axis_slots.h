// The slots of one grid axis: widths alternate thin, wide, thin, ... from index 0.
#pragma once

namespace marble_maze {

/// The slot layout along one axis of the tile grid. Even indices are thin slots (walls, posts,
/// the floor slab), odd indices wide ones (cells), as in the seed's prototype; equal widths give a
/// uniform grid. Every lookup is a closed formula, so its cost does not depend on the slot count.
class AxisSlots {
 public:
  AxisSlots() = default;
  AxisSlots(double thin, double wide, int count)
      : thin_(thin), wide_(wide), count_(count), per_period_(1.0 / (thin + wide)) {}
  static AxisSlots uniform(double width, int count) { return AxisSlots(width, width, count); }

  int count() const { return count_; }
  double thin() const { return thin_; }
  double wide() const { return wide_; }
  bool isUniform() const { return thin_ == wide_; }

  /// Lower boundary of slot `index` (any integer; slot 0 starts at 0).
  double lower(int index) const {
    const int pairs = index >= 0 ? index / 2 : -((1 - index) / 2);
    const int odd = index - 2 * pairs;
    return pairs * period() + odd * thin_;
  }
  double upper(int index) const { return lower(index + 1); }
  double width(int index) const { return (index % 2 == 0) ? thin_ : wide_; }
  double length() const { return lower(count_); }
  double centre(int index) const { return 0.5 * (lower(index) + upper(index)); }

  /// Index of the slot containing coordinate x, unclamped (negative or >= count outside the grid).
  /// A point on a boundary belongs to the upper slot.
  int slotAt(double x) const {
    // A product, not a quotient: this runs several times a step, and a division costs as much
    // as the rest of it.
    double pairs = x * per_period_;
    // Clamped so that the conversion to int is defined; NaN fails the first test and goes low.
    if (!(pairs > -1e8)) pairs = -1e8;
    if (pairs > 1e8) pairs = 1e8;
    int whole = static_cast<int>(pairs);  // towards zero; floor below, without a libm call
    if (whole > pairs) --whole;
    double rest = x - whole * period();
    // The product may round across a period's boundary: the remainder decides.
    if (rest < 0) {
      --whole;
      rest = x - whole * period();
    } else if (rest >= period()) {
      ++whole;
      rest = x - whole * period();
    }
    return 2 * whole + (rest >= thin_ ? 1 : 0);
  }

 private:
  double period() const { return thin_ + wide_; }

  double thin_ = 1.0;
  double wide_ = 1.0;
  int count_ = 0;
  double per_period_ = 0.5;  // 1 / period()
};

}  // namespace marble_maze
