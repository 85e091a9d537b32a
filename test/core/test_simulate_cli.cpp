// The headless runner as a user calls it.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace {

struct Result {
  int status;
  std::string output;  // standard output and error
};

Result runSimulate(const std::string& args) {
  const std::string command = std::string(SIMULATE_PATH) + " " + args + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

std::string readFile(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

std::string tempPath(const std::string& name) {
  return (testing::TempDir() + "/marble_maze_" + name);
}

TEST(SimulateCli, TwoRunsWriteByteIdenticalTrajectories) {
  const std::string schedule = tempPath("tilt.csv");
  std::ofstream(schedule) << "t,roll,pitch\n0,0,0\n0.5,0.1,-0.05\n1.5,-0.1,0.1\n";
  const std::string args = "--tilt-csv " + schedule + " --duration 2 --quiet --set substeps=2";
  ASSERT_EQ(runSimulate(args + " --out " + tempPath("a.csv")).status, 0);
  ASSERT_EQ(runSimulate(args + " --out " + tempPath("b.csv")).status, 0);
  const std::string a = readFile(tempPath("a.csv")), b = readFile(tempPath("b.csv"));
  EXPECT_GT(a.size(), 100000u);  // 2001 rows were written
  EXPECT_EQ(a, b);
  EXPECT_EQ(a.substr(0, a.find('\n')), "t,x,y,z,vx,vy,vz,wx,wy,wz,roll,pitch,contacts,phase");
}

TEST(SimulateCli, ATiltMovesTheMarbleAndTheSummarySaysWhatHappened) {
  const Result r = runSimulate("--tilt 0.1,0 --duration 1");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("maze classic"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ran 1000 steps"), std::string::npos) << r.output;
}

TEST(SimulateCli, ATiltBeyondTheLimitIsClampedLikeAnyTilt) {
  const std::string out = tempPath("steep.csv");
  ASSERT_EQ(runSimulate("--tilt 0.5,0 --duration 0.01 --quiet --out " + out).status, 0);
  const std::string rows = readFile(out);
  const std::string first = rows.substr(rows.find('\n') + 1);
  // roll, the 11th column, starts at the 10 degree limit
  std::istringstream row(first.substr(0, first.find('\n')));
  std::string field;
  for (int i = 0; i < 11; ++i) std::getline(row, field, ',');
  EXPECT_NEAR(std::stod(field), 0.17453292519943295, 1e-8);
  EXPECT_EQ(runSimulate("--tilt 0.25,0 --set tilt_limit=0.3 --duration 0.01 --quiet").status, 0);
}

TEST(SimulateCli, WrongFlagsAndValuesExitWithTwoAndSayWhy) {
  const std::pair<std::string, std::string> cases[] = {
      {"--bogus 1", "unknown option '--bogus'"},
      {"--tilt 0.1", "--tilt: expected ROLL,PITCH"},
      {"--duration abc", "--duration: expected a number"},
      {"--set restitution=2", "restitution: 2 is out of range [0, 1]"},
      {"--set nokey=1", "unknown parameter 'nokey'"},
      {"--set model", "--set: expected KEY=VALUE"},
      {"--maze /nonexistent/maze.yaml", "/nonexistent/maze.yaml"},
      {"--tilt-csv /nonexistent/tilt.csv", "cannot read file"},
      {"--duration", "--duration: needs a value"},
      {"--set start_velocity=1e158,0,0", "start_velocity: 1e+158 m/s is more than"},
      {"--set step=0", "step: 0 is out of range"},
  };
  for (const auto& [args, message] : cases) {
    const Result r = runSimulate(args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << " -> " << r.output;
  }
}

TEST(SimulateCli, EachIntegratorAndPresetRunsAndAWrongOneIsRefusedWithTheChoices) {
  for (const char* integrator : {"semi_implicit_euler", "velocity_verlet", "rk4"}) {
    const Result r =
        runSimulate(std::string("--tilt 0.1,0 --duration 0.5 --set integrator=") + integrator);
    EXPECT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find(std::string("integrator ") + integrator), std::string::npos)
        << r.output;
  }
  const std::pair<std::string, std::string> presets[] = {{"realtime", "step 0.001 s x 1"},
                                                         {"fast", "step 0.005 s x 1"},
                                                         {"accurate", "step 0.0001 s"}};
  for (const auto& [preset, says] : presets) {
    const Result r = runSimulate("--tilt 0.1,0 --duration 0.5 --set preset=" + preset);
    EXPECT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find(says), std::string::npos) << preset << ": " << r.output;
  }
  const Result later = runSimulate("--duration 0.1 --set preset=fast --set step=0.002");
  EXPECT_NE(later.output.find("step 0.002 s"), std::string::npos) << later.output;
  const Result wrong = runSimulate("--set integrator=euler");
  EXPECT_EQ(wrong.status, 2);
  EXPECT_NE(wrong.output.find("expected one of 'semi_implicit_euler', 'velocity_verlet' or 'rk4'"),
            std::string::npos)
      << wrong.output;
  EXPECT_EQ(runSimulate("--set preset=slow").status, 2);
}

TEST(SimulateCli, EveryStepFromATenthOfAMillisecondToTwentyRunsWithDefaultSettings) {
  // The bounce threshold follows the step: no other key needs changing.
  for (const char* integrator : {"semi_implicit_euler", "velocity_verlet", "rk4"})
    for (const char* step : {"0.0001", "0.001", "0.007", "0.02"}) {
      const Result r = runSimulate(std::string("--tilt 0.1,0 --duration 0.2 --set step=") + step +
                                   " --set integrator=" + integrator);
      EXPECT_EQ(r.status, 0) << integrator << " " << step << ": " << r.output;
    }
}

TEST(SimulateCli, HelpListsEveryKey) {
  const Result r = runSimulate("--help");
  EXPECT_EQ(r.status, 0);
  for (const char* key : {"preset", "integrator", "model", "step", "substeps", "restitution",
                          "friction", "rolling_resistance", "bounce_threshold", "drag_coefficient",
                          "start_position", "start_velocity", "tilt_limit", "tilt_rate_limit"})
    EXPECT_NE(r.output.find(std::string("  ") + key), std::string::npos) << key;
}

}  // namespace
