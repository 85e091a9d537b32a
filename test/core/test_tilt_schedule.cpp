// The tilt programme of the runner (--tilt-csv): its values between and beyond its rows, and
// each way a file can be wrong, named with its line.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "marble_maze/params.h"
#include "marble_maze/tilt_schedule.h"

namespace marble_maze {
namespace {

/// The message parse throws for `text`, or "".
std::string errorOf(const std::string& text) {
  try {
    TiltSchedule::parse(text, "prog.csv");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(TiltSchedule, IsLinearBetweenRowsAndHeldBeyondThem) {
  const TiltSchedule s = TiltSchedule::parse(
      "t,roll,pitch\n# a comment\n1,0.1,0\n3,0.3,-0.2\n"
      "4,0,0\n",
      "prog.csv");
  EXPECT_DOUBLE_EQ(s.at(0).roll, 0.1);  // held before the first row
  EXPECT_DOUBLE_EQ(s.at(2).roll, 0.2);
  EXPECT_DOUBLE_EQ(s.at(2).pitch, -0.1);
  EXPECT_DOUBLE_EQ(s.at(3).roll, 0.3);  // exactly on a row
  EXPECT_DOUBLE_EQ(s.at(3.5).pitch, -0.1);
  EXPECT_DOUBLE_EQ(s.at(99).roll, 0.0);  // held after the last
  EXPECT_DOUBLE_EQ(s.duration(), 4.0);
}

TEST(TiltSchedule, ALongProgrammeIsLookedUpAsFastAsAShortOne) {
  // 100,000 rows, each looked up: by bisection, a fraction of a second; a walk from the front
  // for each would take minutes. (A count of the work, not a timing: the values must be right.)
  std::string text;
  // (Row k tilts k times 1e-5 rad, written exactly as k e-5.)
  for (int k = 0; k < 100000; ++k) text += std::to_string(k) + "," + std::to_string(k) + "e-5,0\n";
  const TiltSchedule s = TiltSchedule::parse(text, "long.csv");
  for (int k = 0; k + 1 < 100000; ++k) ASSERT_NEAR(s.at(k + 0.5).roll, (k + 0.5) * 1e-5, 1e-15);
}

TEST(TiltSchedule, LookedUpFromARowItIsTheProgrammesValueToTheBitInAnyOrder) {
  // Uneven rows; times read forward in steps shorter and longer than a row, on the rows
  // themselves, backward, at random, before the first row and past the last, from any row;
  // each value against the rows' own interpolation, worked out here by a walk over them.
  const std::vector<TiltSchedule::Point> rows = {
      {0, 0.1, -0.2}, {0.3, 0.15, 0}, {0.35, -0.1, 0.05}, {1, 0.2, 0.2}, {2.5, 0, -0.1}};
  std::string text;
  for (const auto& r : rows)
    text += exactText(r.time) + "," + exactText(r.roll) + "," + exactText(r.pitch) + "\n";
  const TiltSchedule s = TiltSchedule::parse(text, "p.csv");
  const auto expected = [&](double t) {
    if (t <= rows.front().time) return rows.front();
    std::size_t i = 1;
    while (i < rows.size() && rows[i].time < t) ++i;
    if (i == rows.size()) return rows.back();
    const auto &a = rows[i - 1], &b = rows[i];
    const double f = (t - a.time) / (b.time - a.time);
    return TiltSchedule::Point{t, a.roll + f * (b.roll - a.roll),
                               a.pitch + f * (b.pitch - a.pitch)};
  };
  std::vector<double> times;
  for (double t = -0.2; t < 2.8; t += 0.013) times.push_back(t);  // forward, several a row
  for (double t : {0.0, 0.3, 0.35, 1.0, 2.5, 0.3, 0.0}) times.push_back(t);  // on rows
  for (double t = 2.7; t > -0.1; t -= 0.29) times.push_back(t);              // backward, by leaps
  std::mt19937_64 random(7);
  for (int k = 0; k < 200; ++k) times.push_back(std::uniform_real_distribution<>(-0.5, 3)(random));
  for (std::size_t start : {std::size_t{0}, std::size_t{3}, std::size_t{5}, std::size_t{1000}}) {
    std::size_t row = start;
    for (double t : times) {
      for (const TiltSchedule::Point& got : {s.at(t, &row), s.at(t)}) {
        ASSERT_EQ(got.roll, expected(t).roll) << "t = " << t << " from row " << start;
        ASSERT_EQ(got.pitch, expected(t).pitch) << "t = " << t << " from row " << start;
      }
    }
  }
}

TEST(TiltSchedule, RowsAreReadAsSpreadsheetsWriteThem) {
  // Windows line ends, spaces around the numbers, a comma ending a row, no newline at the end.
  const TiltSchedule s = TiltSchedule::parse(
      "t,roll,pitch\r\n0, 0.25 ,-0.125\r\n\r\n  \n2,0.5,0.75,\n4,-0.5,0.0625", "prog.csv");
  EXPECT_EQ(s.duration(), 4.0);
  EXPECT_EQ(s.at(0).roll, 0.25);
  EXPECT_EQ(s.at(0).pitch, -0.125);
  EXPECT_EQ(s.at(2).roll, 0.5);
  EXPECT_EQ(s.at(2).pitch, 0.75);
  EXPECT_EQ(s.at(4).roll, -0.5);
  EXPECT_EQ(s.at(4).pitch, 0.0625);
  // Each field is one number: an empty field, or a fourth number, is refused (a comma ending a
  // row is no field), naming its line, counted with the blank and comment lines before it.
  EXPECT_EQ(errorOf("0,0,0\r\n\r\n# c\n  \n1,,0\n"),
            "prog.csv:5: expected three numbers t,roll,pitch (s, rad, rad), got '1,,0'");
  EXPECT_EQ(errorOf("0,0,0\r\n1,0,0,0\r\n"),
            "prog.csv:2: expected three numbers t,roll,pitch (s, rad, rad), got '1,0,0,0'");
  EXPECT_EQ(errorOf("0,0,0\n,1,0\n"),
            "prog.csv:2: expected three numbers t,roll,pitch (s, rad, rad), got ',1,0'");
}

TEST(TiltSchedule, EachWrongFileIsRefusedNamingItsLine) {
  EXPECT_EQ(errorOf("0,0.1,0\n1,x,0\n"),
            "prog.csv:2: expected three numbers t,roll,pitch (s, "
            "rad, rad), got '1,x,0'");
  EXPECT_EQ(errorOf("0,0.1\n"),
            "prog.csv:1: expected three numbers t,roll,pitch (s, rad, rad), got '0,0.1'");
  EXPECT_EQ(errorOf("0,0,0\n2.5,0,0\n1,0,0\n"), "prog.csv:3: times must increase, got 1 after 2.5");
  EXPECT_EQ(errorOf("0,nan,0\n"),
            "prog.csv:1: expected three numbers t,roll,pitch (s, rad, rad), got '0,nan,0'");
  EXPECT_EQ(errorOf("t,roll,pitch\n"), "prog.csv: no rows t,roll,pitch");
  // One header row, the first: words further down are a mistake, not another header.
  EXPECT_EQ(errorOf("# a comment\nt,roll,pitch\n0,0,0\n"), "");
  EXPECT_EQ(errorOf("t,roll,pitch\nO,0,0\n1,0.1,0\n"),
            "prog.csv:2: expected three numbers t,roll,pitch (s, rad, rad), got 'O,0,0'");
  // Angles within a quarter turn (the largest tilt_limit): 1e308 would overflow between rows.
  EXPECT_EQ(errorOf("0,0,0\n0.001,1e308,0\n"),
            "prog.csv:2: roll: 1e+308 rad is more than a quarter turn (1.5707963267948966 rad)");
  EXPECT_EQ(errorOf("0,0,-1.6\n"),
            "prog.csv:1: pitch: -1.6 rad is more than a quarter turn (1.5707963267948966 rad)");
  EXPECT_EQ(errorOf("0,1.5707963267948966,0\n"), "");
  EXPECT_EQ(errorOf(""), "prog.csv: no rows t,roll,pitch");
  try {
    TiltSchedule::load("/nonexistent/prog.csv");
    FAIL() << "an unreadable file was read";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/prog.csv: cannot read file");
  }
}

}  // namespace
}  // namespace marble_maze
