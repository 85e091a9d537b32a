// The runner's CSV files: a simulation's trajectory, a row a written step, and its events. Every
// number is in its shortest form that reads back exactly (exact_text.h), so that a file compares
// bit for bit with another run's.
#pragma once

#include <string>

#include "marble_maze/events.h"
#include "marble_maze/simulation.h"

namespace marble_maze {

/// The trajectory's first line: time, the marble's position in the world, its velocity and spin,
/// the board's tilt, its contacts and its phase.
extern const char kTrajectoryColumns[];

/// The events' first line: time, kind, the tile, the speed.
extern const char kEventColumns[];

/// "free", "in_hole", "at_goal" or "off_board".
const char* phaseName(MarblePhase phase);

/// Appends the simulation's state now as a trajectory row, with its newline.
void appendTrajectoryRow(std::string* out, const Simulation& sim);

/// Appends an event as a row, with its newline.
void appendEventRow(std::string* out, const Event& event);

}  // namespace marble_maze
