// The trade program's short run (make test), and its full sweep (make check, which runs the
// program and names its CSV in MARBLE_MAZE_TRADEOFF_CSV): what it measures agrees with what each
// scheme is known to do.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

/// One CSV row of the trade program, by column name.
using Row = std::map<std::string, std::string>;

std::vector<std::string> split(std::string line) {
  if (!line.empty() && line.back() == '\n') line.pop_back();
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

std::vector<Row> rowsOf(const std::vector<std::string>& lines) {
  std::vector<Row> rows;
  if (lines.empty()) return rows;
  const auto header = split(lines[0]);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto fields = split(lines[i]);
    EXPECT_EQ(fields.size(), header.size()) << lines[i];
    Row row;
    for (std::size_t k = 0; k < fields.size() && k < header.size(); ++k) row[header[k]] = fields[k];
    rows.push_back(row);
  }
  return rows;
}

std::vector<Row> runQuick() {
  FILE* pipe = popen((std::string(TRADEOFF_PATH) + " --quick 2>/dev/null").c_str(), "r");
  std::vector<std::string> lines;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) lines.emplace_back(buffer);
  EXPECT_EQ(pclose(pipe), 0);
  return rowsOf(lines);
}

double number(const Row& row, const std::string& key) {
  return std::stod(row.at(key));
}

TEST(TradeoffCli, TheQuickRunMeasuresWhatEachSchemeIsKnownToDo) {
  const std::vector<Row> rows = runQuick();
  ASSERT_EQ(rows.size(), 12u);  // 2 models x 3 integrators x 2 steps
  for (const Row& r : rows) {
    const std::string what = r.at("model") + " " + r.at("integrator") + " " + r.at("step");
    const double step = number(r, "step");
    EXPECT_GT(number(r, "ns_per_simulated_s"), 0) << what;
    // The play error: a statistic over starts, its 90th percentile at or above its median, and
    // within the classic maze (0.28 m across).
    EXPECT_GE(number(r, "play_error_median_m"), 0) << what;
    EXPECT_GE(number(r, "play_error_p90_m"), number(r, "play_error_median_m")) << what;
    EXPECT_LT(number(r, "play_error_p90_m"), 0.3) << what;
    if (r.at("integrator") == "semi_implicit_euler") {
      // First order: the incline's error is exactly step / t (t = 1 s).
      EXPECT_NEAR(number(r, "incline"), step, 1e-6 * step) << what;
    } else {
      // Exact under constant forces: rounding only.
      EXPECT_LT(number(r, "incline"), 1e-12) << what;
      EXPECT_LT(number(r, "bounce"), 1e-12) << what;
    }
    if (r.at("integrator") == "rk4") {
      EXPECT_LT(number(r, "drag"), 1e-12) << what;
    }
    if (r.at("integrator") == "velocity_verlet") {
      EXPECT_GT(number(r, "drag"), 1e-12) << what;
    }
  }
  const auto find = [&](const char* integrator, const char* step) {
    for (const Row& r : rows)
      if (r.at("model") == "rolling" && r.at("integrator") == integrator && r.at("step") == step)
        return r;
    ADD_FAILURE() << integrator << " " << step;
    return Row();
  };
  // Velocity Verlet's drag error is second order: a ten times longer step, a hundred times more.
  const double ratio = number(find("velocity_verlet", "0.01"), "drag") /
                       number(find("velocity_verlet", "0.001"), "drag");
  EXPECT_NEAR(ratio, 100, 10);
  // And so is it on a board turning at a constant rate.
  const double turning = number(find("velocity_verlet", "0.01"), "turning_board") /
                         number(find("velocity_verlet", "0.001"), "turning_board");
  EXPECT_NEAR(turning, 100, 10);
  EXPECT_EQ(find("velocity_verlet", "0.001").at("preset"), "realtime");
}

TEST(TradeoffCli, TheFullSweepMeasuresEveryOptionAsEachSchemeIsKnownTo) {
  const char* path = std::getenv("MARBLE_MAZE_TRADEOFF_CSV");
  if (!path) GTEST_SKIP() << "make check runs the sweep and names its CSV";
  std::ifstream file(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(file, line);) lines.push_back(line);
  const std::vector<Row> rows = rowsOf(lines);
  // 2 models x 3 integrators x 8 steps x 3 substep counts.
  ASSERT_EQ(rows.size(), 144u);
  int presets = 0;
  for (const Row& r : rows) {
    const std::string what =
        r.at("model") + " " + r.at("integrator") + " " + r.at("step") + " x " + r.at("substeps");
    const double h = number(r, "step") / number(r, "substeps");
    // Rounding grows with the substeps taken: some 1e-16 of the result each, over 1 s.
    const double rounding = std::max(1e-12, 2e-16 / h);
    EXPECT_GT(number(r, "ns_per_simulated_s"), 0) << what;
    EXPECT_GE(number(r, "play_error_p90_m"), number(r, "play_error_median_m")) << what;
    if (r.at("integrator") == "semi_implicit_euler") {
      EXPECT_NEAR(number(r, "incline"), h, 1e-6 * h + rounding) << what;  // first order: h / t
    } else {
      EXPECT_LT(number(r, "incline"), rounding) << what;  // exact under constant forces
      EXPECT_LT(number(r, "bounce"), rounding) << what;
    }
    if (r.at("integrator") == "rk4") EXPECT_LT(number(r, "drag"), rounding) << what;
    presets += !r.at("preset").empty();
  }
  EXPECT_EQ(presets, 3);  // realtime, fast, accurate
  // The orders on drag, one substep, from 1 to 10 ms: velocity Verlet's error a hundred times
  // larger, semi-implicit Euler's ten times.
  const auto drag = [&](const char* model, const char* integrator, const char* step) {
    for (const Row& r : rows)
      if (r.at("model") == model && r.at("integrator") == integrator && r.at("step") == step &&
          r.at("substeps") == "1")
        return number(r, "drag");
    ADD_FAILURE() << model << " " << integrator << " " << step;
    return 1.0;
  };
  for (const char* model : {"smooth", "rolling"}) {
    EXPECT_NEAR(drag(model, "velocity_verlet", "0.01") / drag(model, "velocity_verlet", "0.001"),
                100, 10)
        << model;
    EXPECT_NEAR(
        drag(model, "semi_implicit_euler", "0.01") / drag(model, "semi_implicit_euler", "0.001"),
        10, 1)
        << model;
  }
}

}  // namespace
