// The runners as a user calls them: simulate on the core, and resimulate for a recorded session.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

struct Result {
  int status;
  std::string output;  // standard output and error
};

Result runProgram(const std::string& program, const std::string& args) {
  const std::string command = program + " " + args + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

Result runSimulate(const std::string& args) {
  return runProgram(SIMULATE_PATH, args);
}
Result runResimulate(const std::string& args) {
  return runProgram(RESIMULATE_PATH, args);
}

std::string readFile(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

/// A scratch file of the running test's own: tests run side by side (gtest's shards) never share
/// one.
std::string tempPath(const std::string& name) {
  return testing::TempDir() + "/marble_maze_" +
         testing::UnitTest::GetInstance()->current_test_info()->name() + "_" + name;
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

TEST(SimulateCli, ADurationThatIsNoWholeNumberOfStepsSaysWhatRuns) {
  const std::string out = tempPath("short.csv");
  const Result r = runSimulate("--set step=0.1 --duration 0.05 --quiet --out " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("--duration 0.05 s is not a whole number of steps of 0.1 s; runs 1 "
                          "step (0.1 s)"),
            std::string::npos)
      << r.output;
  const std::string rows = readFile(out);  // the header, the start and the one step
  EXPECT_EQ(std::count(rows.begin(), rows.end(), '\n'), 3) << rows;
  EXPECT_EQ(runSimulate("--duration 2 --quiet").output, "");  // a whole number: nothing said
}

TEST(SimulateCli, ATiltBeyondTheLimitIsClampedLikeAnyTilt) {
  const std::string out = tempPath("steep.csv");
  const Result steep = runSimulate("--tilt 0.5,0 --duration 0.01 --quiet --out " + out);
  ASSERT_EQ(steep.status, 0);
  EXPECT_NE(steep.output.find("up to 0.5 rad, beyond tilt_limit 0.174533 rad; clamped"),
            std::string::npos)
      << steep.output;  // said, as the node says it
  const std::string rows = readFile(out);
  const std::string first = rows.substr(rows.find('\n') + 1);
  // roll, the 11th column, starts at the 10 degree limit
  std::istringstream row(first.substr(0, first.find('\n')));
  std::string field;
  for (int i = 0; i < 11; ++i) std::getline(row, field, ',');
  EXPECT_NEAR(std::stod(field), 0.17453292519943295, 1e-8);
  const Result within = runSimulate("--tilt 0.25,0 --set tilt_limit=0.3 --duration 0.01 --quiet");
  EXPECT_EQ(within.status, 0);
  EXPECT_EQ(within.output.find("clamped"), std::string::npos) << within.output;
}

/// The board's roll in each row of the trajectory of `simulate ARGS --quiet --out FILE`, from
/// t = 0 on.
std::vector<double> rolls(const std::string& args) {
  const std::string out = tempPath("rolls.csv");
  std::remove(out.c_str());
  EXPECT_EQ(runSimulate(args + " --quiet --out " + out).status, 0) << args;
  std::istringstream rows(readFile(out));
  std::vector<double> found;
  std::string line;
  std::getline(rows, line);  // the header
  while (std::getline(rows, line)) {
    std::istringstream row(line);
    std::string field;
    for (int i = 0; i < 11; ++i) std::getline(row, field, ',');  // roll is the 11th column
    found.push_back(std::stod(field));
  }
  return found;
}

/// The board's roll in the trajectory's first row (at t = 0) of `simulate ARGS --out FILE`.
double firstRoll(const std::string& args) {
  const std::vector<double> r = rolls(args + " --duration 0.01");
  return r.empty() ? NAN : r.front();
}

TEST(SimulateCli, EachStepTakesTheTiltProgrammeAtItsStart) {
  // The programme is level until 10 ms, then rolls: the step from 10 to 11 ms takes its value at
  // 10 ms (level), as the node takes a command stamped at a step's start; the next one moves.
  // (Taken at each step's end, the board led it by a step: rolling by 11 ms.)
  const std::string programme = tempPath("ramp.csv");
  std::ofstream(programme) << "0,0,0\n0.01,0,0\n0.02,0.1,0\n";
  const std::vector<double> r = rolls("--tilt-csv " + programme + " --duration 0.012");
  ASSERT_EQ(r.size(), 13u);  // t = 0, 1, ..., 12 ms
  EXPECT_EQ(r[11], 0.0);
  EXPECT_GT(r[12], 0.0);
}

TEST(SimulateCli, AnInitialTiltInTheMazeFileOrASetOneOutranksTheProgramsFirstTilt) {
  const std::string maze = tempPath("tilted.yaml");
  std::ofstream(maze) << "grid:\n  x: [0.005, 0.02]\n  y: [0.005, 0.02]\n  z: [0.005, 0.012]\n"
                         "layout: |\n  +-+-+-+\n  |S   G|\n  +-+-+-+\n"
                         "physics:\n  initial_roll: 0.05\n";
  EXPECT_EQ(firstRoll("--maze " + maze + " --tilt 0,0"), 0.05);  // the file's
  EXPECT_EQ(firstRoll("--maze " + maze + " --tilt 0,0 --set initial_roll=-0.02"), -0.02);
  EXPECT_EQ(firstRoll("--tilt 0.03,0"), 0.03);  // else the program's first tilt
}

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// Column `column` of the trajectory row at time t (the CSV written with --out).
double trajectoryAt(const std::string& csv, double t, int column) {
  for (const std::string& line : linesOf(csv)) {
    std::vector<std::string> fields;
    std::istringstream row(line);
    for (std::string field; std::getline(row, field, ',');) fields.push_back(field);
    if (fields.size() == 14 && fields[0] != "t" && std::abs(std::stod(fields[0]) - t) < 1e-9)
      return std::stod(fields[column]);
  }
  ADD_FAILURE() << "no row at t = " << t;
  return 0;
}

TEST(SimulateCli, AfterTheProgramTheTiltTimeoutLevelsTheBoardAsTheNodeDoes) {
  // The program's last row is at 0.2 s: its last command acts at the step starting then, and the
  // board holds it until --tilt-timeout has passed since (0.5 s), then levels under its servo.
  const std::string program = tempPath("short_program.csv");
  const std::string csv = tempPath("timeout.csv");
  std::ofstream(program) << "t,roll,pitch\n0,0.1,0\n0.2,0.1,0\n";
  const int kRoll = 10;
  ASSERT_EQ(runSimulate("--tilt-csv " + program + " --tilt-timeout 0.3 --duration 1 --quiet" +
                        " --out " + csv)
                .status,
            0);
  const std::string timed = readFile(csv);
  EXPECT_EQ(trajectoryAt(timed, 0.5, kRoll), 0.1);  // held to the step
  EXPECT_LT(trajectoryAt(timed, 0.502, kRoll), 0.1);
  EXPECT_LT(trajectoryAt(timed, 1.0, kRoll), 0.1 * std::exp(-0.4 / 0.05) * 1.5);  // the servo's lag
  ASSERT_EQ(runSimulate("--tilt-csv " + program + " --duration 1 --quiet --out " + csv).status, 0);
  EXPECT_EQ(trajectoryAt(readFile(csv), 1.0, kRoll), 0.1);  // no timeout: the tilt holds
}

TEST(SimulateCli, TheAutoResetPutsTheMarbleBackAfterAHoleAsTheNodeDoes) {
  // The board lowered towards +x: the marble rolls from the start into the hole beside it.
  const std::string maze = tempPath("hole_beside.yaml");
  std::ofstream(maze) << "grid:\n  x: [0.005, 0.02]\n  y: [0.005, 0.02]\n  z: [0.005, 0.012]\n"
                         "layout: |\n  +-+-+-+\n  |S O G|\n  +-+-+-+\n";
  const auto holes = [&](const std::string& flags) {
    const Result r = runSimulate("--maze " + maze + " --tilt 0,0.05 --duration 3 --quiet " +
                                 "--events - " + flags);
    EXPECT_EQ(r.status, 0) << r.output;
    int count = 0;
    for (const std::string& line : linesOf(r.output)) count += line.find(",hole,") != line.npos;
    return count;
  };
  EXPECT_EQ(holes(""), 1);                  // held in the hole
  EXPECT_GE(holes("--auto-reset 0.5"), 2);  // put back on the start, into the hole again
}

TEST(SimulateCli, WrongFlagsAndValuesExitWithTwoAndSayWhy) {
  // (Outside the working directory: should the refusal fail, nothing is written there.)
  const std::string csv = tempPath("same.csv");
  const std::string csv_again = csv.substr(0, csv.rfind('/')) + "/." + csv.substr(csv.rfind('/'));
  const std::pair<std::string, std::string> cases[] = {
      {"--bogus 1", "unknown option '--bogus'"},
      {"stray", "unknown argument 'stray'"},
      {"--tilt 0.1", "--tilt: expected ROLL,PITCH"},
      {"--duration abc", "--duration: expected a number"},
      {"--set restitution=2", "restitution: 2 is out of range [0, 1]"},
      {"--set nokey=1", "--set 'nokey': unknown parameter (known: preset, "},
      {"--set model", "--set: expected KEY=VALUE"},
      {"--maze /nonexistent/maze.yaml", "/nonexistent/maze.yaml"},
      {"--tilt-csv /nonexistent/tilt.csv", "cannot read file"},
      {"--duration", "--duration: needs a value"},
      {"--set start_velocity=1e158,0,0", "start_velocity: 1e+158 m/s is more than"},
      {"--set step=0", "step: 0 is out of range"},
      // Messages that name the problem; settings the marble cannot start in.
      {"--set step=1e-400", "step: '1e-400' underflows"},
      {"--set gravity=1e400", "gravity: '1e400' overflows"},
      {"--every 1e12", "--every: expected a whole number from 1 to 2147483647, got '1e12'"},
      {"--every 1e300", "--every: expected a whole number from 1 to 2147483647"},
      {"--every 2.5", "--every: expected a whole number"},
      {"--set start_position=0,0,0.006",
       "--set start_position: a marble of radius 0.006 m cannot start there: inside tile (10, 8, "
       "1)"},
      // (Refused with the rest of the scene, the value is still named as the --set's.)
      {"--set marble_radius=0.015", "--set marble_radius: a marble of radius 0.015 m does not fit"},
      {"--set marble_radius=0.015", "start cell (1, 15, the 'S' at <embedded:classic>:13:4)"},
      {"--maze /dev/zero", "/dev/zero: more than 16 MB"},  // a device read without end
      {"--tilt-csv /dev/zero", "--tilt-csv: /dev/zero: more than 16 MB"},
      {"--maze /tmp", "/tmp: is a directory"},
      {"--maze clasic", "clasic: neither a built-in maze (classic, brio, prototype) nor a file"},
      {"--quite", "unknown option '--quite'"},  // last, with no value after it
      {"--tilt-timeout -1", "--tilt-timeout: expected 0..1e6 seconds, got '-1'"},
      {"--auto-reset soon", "--auto-reset: expected a number"},
      // A recorded session is resimulate's.
      {"--bag session.bag", "--bag: a recorded session is re-simulated by resimulate"},
      {"--check", "--check: only with resimulate --bag"},
      // Two CSVs in one file would garble both; a third tilt value is not silently dropped.
      {"--out " + csv + " --events " + csv, "--events: '" + csv + "' is --out's too"},
      {"--out - --events -", "--events: '-' is --out's too"},
      {"--out " + csv_again + " --events " + csv, "--events: '" + csv + "' is --out's too"},
      {"--out - --events /dev/stdout", "--events: '/dev/stdout' is --out's too"},
      {"--tilt 0.1,0.1,0.1", "--tilt: expected ROLL,PITCH, got '0.1,0.1,0.1'"},
      // A flag given again would silently undo the first; a tilt program given twice likewise.
      {"--maze classic --maze prototype", "--maze: given twice ('prototype' after the first)"},
      {"--duration 1 --duration 2", "--duration: given twice ('2' after the first)"},
      {"--tilt 0.1,0 --tilt-csv /nonexistent.csv", "--tilt-csv: not with --tilt"},
  };
  for (const auto& [args, message] : cases) {
    const Result r = runSimulate(args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << " -> " << r.output;
  }
}

TEST(ResimulateCli, WrongFlagsExitWithTwoAndSayWhy) {
  // (The bag's own refusals, a bag without states or inputs, are test_record_replay.py's.)
  const std::pair<std::string, std::string> cases[] = {
      {"", "resimulate: --bag: required"},
      {"--check", "--bag: required"},
      {"--bag session.bag --maze classic", "--maze: not with --bag, whose session sets it"},
      {"--tilt 0,0 --bag session.bag", "--tilt: not with --bag"},
      {"--bag session.bag --duration 3", "--duration: not with --bag"},
      {"--bag session.bag --auto-reset 2", "--auto-reset: not with --bag"},
      {"--bag /nonexistent/session.bag", "--bag: "},
      // Other physics make other states: --check would only fail, or find nothing to compare.
      {"--bag session.bag --check --set preset=fast",
       "--check: not with --set (preset): the recorded states are those of the recorded physics"},
  };
  for (const auto& [args, message] : cases) {
    const Result r = runResimulate(args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << " -> " << r.output;
  }
  const Result help = runResimulate("--help");
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.output.find("Usage: resimulate --bag FILE"), std::string::npos);
}

TEST(SimulateCli, ARefusalNamesTheSetOnlyWhenASetGaveTheValue) {
  // Cells 10 mm wide: the default 6 mm marble does not fit its start cell, whatever is set.
  const std::string maze = tempPath("narrow.yaml");
  std::ofstream(maze) << "grid:\n  x: [0.005, 0.01]\n  y: [0.005, 0.01]\n  z: [0.005, 0.012]\n"
                         "layout: |\n  +-+-+-+\n  |S   G|\n  +-+-+-+\n";
  const Result other = runSimulate("--maze " + maze + " --set restitution=0.5");
  EXPECT_EQ(other.status, 2);
  EXPECT_NE(other.output.find("simulate: marble_radius: a marble of radius 0.006 m does not fit"),
            std::string::npos)
      << other.output;
  const Result set = runSimulate("--maze " + maze + " --set marble_radius=0.006");
  EXPECT_EQ(set.status, 2);
  EXPECT_NE(set.output.find("simulate: --set marble_radius: a marble of radius 0.006 m"),
            std::string::npos)
      << set.output;
  // A refusal of two keys is the --sets' only when both are theirs: here the file's initial
  // roll is beyond the tilt limit set, the initial pitch set blameless.
  const std::string tilted = tempPath("tilted_start.yaml");
  std::ofstream(tilted) << "grid:\n  x: [0.005, 0.02]\n  y: [0.005, 0.02]\n  z: [0.005, 0.012]\n"
                           "layout: |\n  +-+-+-+\n  |S   G|\n  +-+-+-+\n"
                           "physics:\n  initial_roll: 0.1\n";
  const Result file =
      runSimulate("--maze " + tilted + " --set initial_pitch=0 --set tilt_limit=0.05");
  EXPECT_EQ(file.status, 2);
  EXPECT_NE(file.output.find("simulate: initial_roll/initial_pitch: beyond tilt_limit 0.05"),
            std::string::npos)
      << file.output;
  const Result both =
      runSimulate("--set initial_roll=0.1 --set initial_pitch=0 --set tilt_limit=0.05");
  EXPECT_EQ(both.status, 2);
  EXPECT_NE(both.output.find("simulate: --set initial_roll/initial_pitch: beyond tilt_limit"),
            std::string::npos)
      << both.output;
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

/// The help's key list read as a user reads it: each "  key [unit]  text (default X)" line, by
/// its key, in the help's order; none when the help has no such list.
std::vector<std::pair<std::string, std::string>> helpKeyLines() {
  const Result help = runSimulate("--help");
  EXPECT_EQ(help.status, 0);
  const std::size_t list = help.output.find("Keys for --set");
  EXPECT_NE(list, std::string::npos) << help.output;
  std::istringstream lines(list == std::string::npos ? "" : help.output.substr(list));
  std::vector<std::pair<std::string, std::string>> keys;
  for (std::string line; std::getline(lines, line);)
    if (line.compare(0, 2, "  ") == 0 && line.rfind("(default ") != std::string::npos)
      keys.emplace_back(line.substr(2, line.find(' ', 2) - 2), line);
  return keys;
}

TEST(SimulateCli, EveryKeyTheHelpListsTakesTheDefaultItShows) {
  // Each key --set must take with the very default the help shows (the list and the parser
  // agree).
  int keys = 0;
  for (const auto& [key, line] : helpKeyLines()) {
    const std::size_t open = line.rfind("(default ");
    const std::string value = line.substr(open + 9, line.size() - open - 10);
    ++keys;
    if (value == "start cell") continue;  // start_position: unset, the maze's start cell
    const Result r = runSimulate("--duration 0.001 --quiet --set " + key + "=" + value);
    EXPECT_EQ(r.status, 0) << key << "=" << value << ": " << r.output;
  }
  EXPECT_GE(keys, 20);  // the table has more than 20 keys
}

TEST(SimulateCli, EveryRangeTheHelpShowsIsTheOneASetIsRefusedBeyond) {
  // Each "..., in [LO, HI] (default X)" line: a value beyond either bound is refused, naming the
  // key and that range.
  int ranges = 0;
  for (const auto& [key, line] : helpKeyLines()) {
    const std::size_t in = line.rfind(", in [");
    if (in == std::string::npos) continue;
    const std::string range = line.substr(in + 5, line.find(']', in) - in - 4);  // "[LO, HI]"
    const double lo = std::stod(range.substr(1)), hi = std::stod(range.substr(range.find(',') + 1));
    ++ranges;
    for (double beyond : {lo - std::max(1.0, std::abs(lo)), hi + std::max(1.0, std::abs(hi))}) {
      std::ostringstream set;
      set << key << "=" << beyond;
      const Result r = runSimulate("--duration 0.001 --quiet --set " + set.str());
      EXPECT_EQ(r.status, 2) << set.str() << ": " << r.output;
      EXPECT_NE(r.output.find("--set " + key + ": "), std::string::npos) << r.output;
      EXPECT_NE(r.output.find(range), std::string::npos) << set.str() << ": " << r.output;
    }
  }
  EXPECT_GE(ranges, 15);
}

}  // namespace
