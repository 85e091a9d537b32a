// The runners' command line (simulate, and resimulate for a recorded session): its options read
// and checked, and the session they ask for built and played, with every refusal a UsageError
// naming the flag or key. Free of ROS and of files written, so that the fuzzer drives it as the
// program does.
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
#include "marble_maze/session.h"
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
  double tilt_timeout =
      0;                  // s without a command before the board levels (the node's ~tilt_timeout)
  double auto_reset = 0;  // s after a hole or the goal before the marble is put back
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

/// The scene and the session the options ask for (not for --bag), played a step at a time by
/// playStep; throws UsageError.
struct Run {
  Scene scene;
  std::unique_ptr<Session> session;
  std::size_t tilt_row = 0;  ///< where the last step's tilt was found in the tilt program
};
Run prepare(const Options& o);

/// Takes the run's next step as the node takes it from a controller playing the tilt program:
/// while the program runs, a command with its value at the step's start (as a controller sends
/// it then, and the node applies a command at the first step that starts at or after its
/// stamp); after its last row, none, so that the board holds that tilt until the tilt timeout
/// levels it. The session's queue, timeouts and auto reset do the rest, as the node's do.
/// Substeps refine the physics between commands, not the program.
void playStep(const Options& o, Run* run);

}  // namespace runner
}  // namespace marble_maze
