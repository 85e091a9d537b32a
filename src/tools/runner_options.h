// The runner's command line (simulate): its options read and checked, and the simulation they
// ask for built, with every refusal a UsageError naming the flag or key. Free of ROS and of
// files written, so that the fuzzer drives it as the program does.
#pragma once

#include <iosfwd>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "marble_maze/maze_file.h"
#include "marble_maze/simulation.h"
#include "marble_maze/tilt_schedule.h"

namespace marble_maze {
namespace runner {

/// A wrong flag or value: exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Options {
  std::string maze = "classic";
  TiltSchedule tilt{0.0, 0.0};
  std::vector<std::pair<std::string, std::string>> sets;
  double duration = 5.0;
  std::string out;     // trajectory CSV, "-" for standard output
  std::string events;  // events CSV
  int every = 1;
  bool quiet = false;
  bool help = false;
  std::string bag;     // a recorded session to re-simulate
  bool check = false;  // and compare with its recorded marble_state
};

/// A physics refusal ("KEY: why", or "KEY/KEY: why") of values --sets may have given: "--set"
/// before it when every key it names a --set gave, else `otherwise` (where the rest came from).
UsageError physicsRefusal(const Options& o, const ParamError& refusal,
                          const std::string& otherwise);

void printHelp(std::ostream& out);
/// The options of `args` (the program's name left out); throws UsageError.
Options parseOptions(const std::vector<std::string>& args);

/// The scene and the simulation the options ask for (not for --bag); throws UsageError.
struct Run {
  Scene scene;
  std::unique_ptr<Simulation> sim;
};
Run prepare(const Options& o);

}  // namespace runner
}  // namespace marble_maze
