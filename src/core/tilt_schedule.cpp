#include "marble_maze/tilt_schedule.h"

#include <algorithm>
#include <cmath>
#include <string_view>

#include "marble_maze/in_quotes.h"
#include "marble_maze/params.h"
#include "marble_maze/text_file.h"

namespace marble_maze {

namespace {

/// The fields of `row` between its commas, as std::getline reads them (a comma that ends the row
/// starts no further one), into `fields`, whose strings keep their storage from row to row.
void splitFields(std::string_view row, std::vector<std::string>* fields) {
  std::size_t count = 0;
  for (std::size_t start = 0; start < row.size(); ++count) {
    const std::size_t comma = std::min(row.find(',', start), row.size());
    if (fields->size() == count) fields->emplace_back();
    (*fields)[count].assign(row.substr(start, comma - start));
    start = comma + 1;
  }
  fields->resize(count);
}

}  // namespace

TiltSchedule TiltSchedule::parse(const std::string& text, const std::string& source) {
  // (Lines and fields are read in place: a stream for each row was more than half the reading.)
  TiltSchedule schedule;
  std::vector<std::string> fields;
  bool first_row = true;
  int number = 0;
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    std::string_view line(text.data() + start, end - start);
    start = end + 1;
    ++number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.find_first_not_of(" \t") == std::string_view::npos || line[0] == '#') continue;
    const auto error = [&](const std::string& message) {
      return std::runtime_error(source + ":" + std::to_string(number) + ": " + message);
    };
    splitFields(line, &fields);
    Point p{};
    const bool numeric = fields.size() == 3 && parseFiniteNumber(fields[0], &p.time) &&
                         parseFiniteNumber(fields[1], &p.roll) &&
                         parseFiniteNumber(fields[2], &p.pitch);
    const bool header = first_row && fields.size() == 3 && !parseFiniteNumber(fields[0], &p.time);
    first_row = false;
    if (!numeric) {
      if (header) continue;  // the first row may name the columns; no other row may be words
      throw error("expected three numbers t,roll,pitch (s, rad, rad), got " +
                  inQuotes(std::string(line)));
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
