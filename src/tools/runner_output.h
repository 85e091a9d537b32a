// What the runners write: the trajectory and events CSVs (marble_maze/csv.h) to files or
// standard output, and the summary.
#pragma once

#include <fstream>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "marble_maze/events.h"
#include "marble_maze/simulation.h"
#include "runner_options.h"

namespace marble_maze {
namespace runner {

/// Where the summary goes: standard error when a CSV is written to standard output.
std::ostream& summaryStream(const Options& o);

/// Opens FILE for writing, or standard output for "-"; null when no file was asked for. Throws
/// UsageError when it cannot be written.
std::ostream* openOutput(const std::string& path, std::unique_ptr<std::ofstream>* holder);

/// Writes the simulation's state now as a trajectory row.
void writeRow(std::ostream& out, const Simulation& sim);

/// Writes the events as CSV rows, when there is an output.
void writeEvents(std::ostream* out, const std::vector<Event>& events);

/// Lists the events but collisions on `s`, one a line, and returns how many collisions there were.
int listFinishes(std::ostream& s, const std::vector<Event>& events);

}  // namespace runner
}  // namespace marble_maze
