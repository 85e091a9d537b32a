// Fuzzes the maze-file parser with whatever text libFuzzer makes of its corpus (fuzz/corpus/maze
// and mazes/: shipped mazes and broken ones). A text is either refused with a MazeFileError that
// names the file (by the parser, or by the simulation for a start_position the file sets where
// the marble cannot be), refused with a ParamError (a marble wider than its start cell), or it
// is a maze a simulation runs on: 20 steps under a tilt, the marble finite.
// Anything else (another exception, a crash, undefined behaviour, a hang) is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "marble_maze/maze_file.h"
#include "marble_maze/simulation.h"

namespace mm = marble_maze;

namespace {

// Mazes of more tiles are parsed but not stepped: building their grid is the test there.
constexpr long kMostSimulatedTiles = 1 << 22;

void check(bool ok) {
  if (!ok) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  mm::Scene scene;
  try {
    scene = mm::parseScene(text, "fuzz.yaml");
  } catch (const mm::MazeFileError& e) {
    check(std::string(e.what()).rfind("fuzz.yaml", 0) == 0);  // it names the file
    return 0;
  }
  const mm::Index3& size3 = scene.maze.size();
  if (static_cast<long>(size3.x()) * size3.y() * size3.z() > kMostSimulatedTiles) return 0;
  try {
    mm::Simulation sim(scene);
    for (int k = 0; k < 20; ++k) {
      sim.setTargetTilt(0.1, -0.05);
      sim.step();
    }
    check(sim.marble().position.allFinite() && sim.marble().velocity.allFinite());
  } catch (const mm::MazeFileError& e) {
    // A start_position the file sets where the marble cannot be: refused at its place in the file.
    check(std::string(e.what()).rfind("fuzz.yaml:", 0) == 0);
  } catch (const mm::ParamError& e) {
    check(e.what()[0] != '\0');  // a marble that cannot start in this maze: refused, named
  }
  return 0;
}
