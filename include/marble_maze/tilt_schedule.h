// A tilt program: board angles against time, read from CSV rows "t,roll,pitch".
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace marble_maze {

/// Piecewise-linear roll and pitch (rad) against time (s); held before the first row and after
/// the last.
class TiltSchedule {
 public:
  struct Point {
    double time;
    double roll;
    double pitch;
  };

  TiltSchedule() = default;
  /// A constant tilt.
  TiltSchedule(double roll, double pitch) : points_{{0.0, roll, pitch}} {}
  /// Parses CSV text: rows "t,roll,pitch" with times increasing; an optional header row and
  /// '#' comment lines. Throws std::runtime_error "SOURCE:LINE: message".
  static TiltSchedule parse(const std::string& text, const std::string& source);
  static TiltSchedule load(const std::string& path);

  Point at(double time) const;
  /// The same value as at(time), looked up from `*row`, where the last such call found its
  /// rows, and leaving there the row it finds: a programme read forward, a step at a time,
  /// takes no search a step. (*row starts at 0; any value is looked up correctly.)
  Point at(double time, std::size_t* row) const;
  double duration() const { return points_.empty() ? 0.0 : points_.back().time; }
  /// The largest |roll| or |pitch| it asks for (rad).
  double largestTilt() const;

 private:
  std::vector<Point> points_;
};

}  // namespace marble_maze
