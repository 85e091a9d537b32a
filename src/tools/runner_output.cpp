#include "runner_output.h"

#include <iostream>

#include "marble_maze/csv.h"

namespace marble_maze {
namespace runner {

std::ostream& summaryStream(const Options& o) {
  return (o.out == "-" || o.events == "-") ? std::cerr : std::cout;
}

std::ostream* openOutput(const std::string& path, std::unique_ptr<std::ofstream>* holder) {
  if (path.empty()) return nullptr;
  if (path == "-") return &std::cout;
  holder->reset(new std::ofstream(path));
  if (!**holder) throw UsageError("cannot write '" + path + "'");
  return holder->get();
}

void writeRow(std::ostream& out, const Simulation& sim) {
  std::string row;
  appendTrajectoryRow(&row, sim);
  out << row;
}

void writeEvents(std::ostream* out, const std::vector<Event>& events) {
  if (!out) return;
  std::string rows;
  for (const Event& e : events) appendEventRow(&rows, e);
  *out << rows;
}

int listFinishes(std::ostream& s, const std::vector<Event>& events) {
  int collisions = 0;
  for (const Event& e : events) {
    if (e.kind == EventKind::Collision) {
      ++collisions;
      continue;
    }
    s << "  t=" << e.time << " s: " << toString(e.kind) << " at tile (" << e.tile.x() << ", "
      << e.tile.y() << ", " << e.tile.z() << ")\n";
  }
  return collisions;
}

}  // namespace runner
}  // namespace marble_maze
