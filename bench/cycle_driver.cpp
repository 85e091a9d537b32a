// The steps make model traces: one of make bench's scenes under its circling tilt, STEPS steps as
// make instructions counts them, of which the model takes SAMPLES windows of WINDOW steps, the
// last of each SAMPLES-th part of the run (so that a maze's many situations are sampled, not one
// corner). Each step of a window comes after a call of cycle_window_mark, and each window ends
// with a call of cycle_window_end: the model finds them in the trace. It prints where the core
// library, this program and the two marks are loaded (under valgrind, where the trace has them),
// so that the model can read each traced instruction from its file.
//
//   marble_maze_cycle_driver CASE STEPS SAMPLES WINDOW   CASE: free_flight, open_floor, maze:CELLS
#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "marble_maze/simulation.h"
#include "step_loop.h"

namespace mm = marble_maze;

/// Mark a step's start and a window's end in the trace; the asm keeps the calls from being folded
/// away, and the two apart.
extern "C" __attribute__((noinline)) void cycle_window_mark() {
  asm volatile("nop");
}
extern "C" __attribute__((noinline)) void cycle_window_end() {
  asm volatile("nop; nop");
}

namespace {

/// The case's scene as make bench builds it, and how often it starts over (0: never).
bool sceneFor(const std::string& name, mm::Scene* scene, std::size_t* restart) {
  if (name == "free_flight") {
    *scene = mm::bench::inFreeFlight(
        {mm::test::generatedMaze(mm::bench::kFreeFlightCells, true), mm::Params()});
    *restart = mm::bench::kFreeFlightRestart;
  } else if (name == "open_floor") {
    *scene = {mm::test::generatedMaze(mm::bench::kOpenFloorCells, false), mm::Params()};
    *restart = mm::bench::kOpenFloorRestart;
  } else if (name.rfind("maze:", 0) == 0) {
    const int cells = std::atoi(name.c_str() + 5);
    if (cells < 2) return false;
    *scene = {mm::test::generatedMaze(cells, true), mm::Params()};
    *restart = 0;
  } else {
    return false;
  }
  return true;
}

/// Where the shared object holding `symbol` is loaded.
void* loadedAt(void* symbol, std::string* path) {
  Dl_info info{};
  if (!dladdr(symbol, &info)) return nullptr;
  *path = info.dli_fname;
  return info.dli_fbase;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: %s free_flight|open_floor|maze:CELLS STEPS SAMPLES WINDOW\n",
                 argv[0]);
    return 2;
  }
  mm::Scene scene;
  std::size_t restart = 0;
  if (!sceneFor(argv[1], &scene, &restart)) {
    std::fprintf(stderr, "case '%s' is none of free_flight, open_floor, maze:CELLS\n", argv[1]);
    return 2;
  }
  const long steps = std::atol(argv[2]), samples = std::atol(argv[3]), window = std::atol(argv[4]);
  if (samples < 1 || window < 1 || steps < samples * window) {
    std::fprintf(stderr, "want STEPS >= SAMPLES x WINDOW, each at least 1\n");
    return 2;
  }
  mm::Simulation sim(scene);
  const auto tilts = mm::bench::circlingTilts(sim.params().step);
  std::size_t n = 0;
  const auto step = [&] {  // as stepUnderCirclingTilt takes one
    const auto& [roll, pitch] = tilts[n++ % tilts.size()];
    sim.setTargetTilt(roll, pitch);
    sim.step();
    if (sim.marble().phase != mm::MarblePhase::Free || (restart && n % restart == 0)) sim.reset();
  };
  std::string core, self;
  void* core_base = loadedAt(reinterpret_cast<void*>(&mm::findContacts), &core);
  void* self_base = loadedAt(reinterpret_cast<void*>(&cycle_window_mark), &self);
  if (!core_base || !self_base) {
    std::fprintf(stderr, "cannot find where the core library or this program is loaded\n");
    return 1;
  }
  std::printf("object %p %s\nobject %p %s\nmark %p\nend %p\n", core_base, core.c_str(), self_base,
              self.c_str(), reinterpret_cast<void*>(&cycle_window_mark),
              reinterpret_cast<void*>(&cycle_window_end));
  std::fflush(stdout);
  const long part = steps / samples;
  for (long i = 0; i < steps; ++i) {
    const long into_part = i % part;
    const bool traced = i < samples * part && into_part >= part - window;
    if (traced) cycle_window_mark();
    step();
    if (traced && into_part == part - 1) cycle_window_end();
  }
  return 0;
}
