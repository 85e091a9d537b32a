// The runner's command line (simulate): its options read and checked, and the simulation they
// ask for built, with every refusal a UsageError naming the flag or key. Free of ROS and of
// files written, so that the fuzzer drives it as the program does.
#pragma once

#include <cstddef>
#include <cstdint>
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

/// The tilt the run sets before step n (1, 2, ...) of `step` seconds: the programme's value at
/// the step's start, as a controller sends it then and the node takes a command at the first
/// step that starts at or after its stamp (taken at the step's end, the board would act on a
/// value a step before a controller could send it). Substeps refine the physics between
/// commands, not the programme. (`row`: where the last step's tilt was found in the
/// programme, which the steps read forward.)
inline TiltSchedule::Point tiltBeforeStep(const Options& o, std::uint64_t n, double step,
                                          std::size_t* row) {
  return o.tilt.at(static_cast<double>(n - 1) * step, row);
}

}  // namespace runner
}  // namespace marble_maze
