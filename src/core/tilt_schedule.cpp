#include "marble_maze/tilt_schedule.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "marble_maze/in_quotes.h"
#include "marble_maze/params.h"
#include "marble_maze/text_file.h"

namespace marble_maze {

TiltSchedule TiltSchedule::parse(const std::string& text, const std::string& source) {
  TiltSchedule schedule;
  std::istringstream in(text);
  std::string line;
  bool first_row = true;
  for (int number = 1; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos || line[0] == '#') continue;
    const auto error = [&](const std::string& message) {
      return std::runtime_error(source + ":" + std::to_string(number) + ": " + message);
    };
    std::vector<std::string> fields;
    std::istringstream row(line);
    for (std::string field; std::getline(row, field, ',');) fields.push_back(field);
    Point p{};
    const bool numeric = fields.size() == 3 && parseFiniteNumber(fields[0], &p.time) &&
                         parseFiniteNumber(fields[1], &p.roll) &&
                         parseFiniteNumber(fields[2], &p.pitch);
    const bool header = first_row && fields.size() == 3 && !parseFiniteNumber(fields[0], &p.time);
    first_row = false;
    if (!numeric) {
      if (header) continue;  // the first row may name the columns; no other row may be words
      throw error("expected three numbers t,roll,pitch (s, rad, rad), got " + inQuotes(line));
    }
    // (A board turns at most a quarter turn, the largest tilt_limit: a larger angle is a mistake,
    // and one near the largest double would overflow between rows.)
    for (const auto& [name, angle] : {std::pair{"roll", p.roll}, {"pitch", p.pitch}})
      if (std::abs(angle) > kQuarterTurn)
        throw error(std::string(name) + ": " + exactText(angle) +
                    " rad is more than a quarter turn (" + exactText(kQuarterTurn) + " rad)");
    if (!schedule.points_.empty() && p.time <= schedule.points_.back().time)
      throw error("times must increase, got " + fields[0] + " after " +
                  exactText(schedule.points_.back().time));
    schedule.points_.push_back(p);
  }
  if (schedule.points_.empty()) throw std::runtime_error(source + ": no rows t,roll,pitch");
  return schedule;
}

TiltSchedule TiltSchedule::load(const std::string& path) {
  return parse(readTextFile(path), path);  // TextFileError is a std::runtime_error
}

TiltSchedule::Point TiltSchedule::at(double time) const {
  std::size_t row = 0;
  return at(time, &row);
}

TiltSchedule::Point TiltSchedule::at(double time, std::size_t* row) const {
  if (points_.empty()) return {time, 0, 0};
  if (time <= points_.front().time) return {time, points_.front().roll, points_.front().pitch};
  if (time > points_.back().time) return {time, points_.back().roll, points_.back().pitch};
  // The first point at or after `time` (past the first): the row's or the next (a programme
  // read forward), else by bisection, so that a long programme costs a step no more than a
  // short one (a walk from the front made a run quadratic in its length).
  const auto first_at_or_after = [&](std::size_t i) {
    return i > 0 && i < points_.size() && points_[i - 1].time < time && time <= points_[i].time;
  };
  std::size_t i = *row;
  if (!first_at_or_after(i) && !first_at_or_after(++i)) {
    i = static_cast<std::size_t>(
        std::lower_bound(points_.begin(), points_.end(), time,
                         [](const Point& p, double t) { return p.time < t; }) -
        points_.begin());
  }
  *row = i;
  const Point &a = points_[i - 1], &b = points_[i];
  const double f = (time - a.time) / (b.time - a.time);
  return {time, a.roll + f * (b.roll - a.roll), a.pitch + f * (b.pitch - a.pitch)};
}

double TiltSchedule::largestTilt() const {
  double largest = 0;
  for (const Point& p : points_) largest = std::max({largest, std::abs(p.roll), std::abs(p.pitch)});
  return largest;
}

}  // namespace marble_maze
