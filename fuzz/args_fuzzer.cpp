// Fuzzes the runners' command line (simulate, resimulate): the input is its arguments, one a line
// (corpus: fuzz/corpus/args). Every command line is either refused with a UsageError that says
// something, or it builds a simulation that then runs (the first 200 steps of it at most, under its
// tilt). Flags that name files to write or read (--out, --events, --bag, --tilt-csv, a --maze path)
// are left to the maze fuzzer and the tests: the fuzzer touches no file.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "runner_options.h"

namespace mm = marble_maze;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  if (text.find('\0') != std::string::npos) return 0;  // no argument of a program holds one
  std::vector<std::string> args;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) args.push_back(line);
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--out" || a == "--events" || a == "--bag" || a == "--tilt-csv") return 0;
    if (a == "--maze" && i + 1 < args.size() && args[i + 1] != "classic" &&
        args[i + 1] != "prototype")
      return 0;
  }
  try {
    const mm::runner::Options o = mm::runner::parseOptions(args);
    if (o.help || !o.bag.empty()) return 0;
    mm::runner::Run run = mm::runner::prepare(o);
    const double step = run.scene.params.step;
    // At most 200 steps and 2000 substeps: the run's start is what is fuzzed, not its length.
    const double steps = std::min(200.0, o.duration / step + 0.5);
    const mm::Simulation& sim = run.session->simulation();
    for (int n = 1; n <= steps && sim.counts().substeps < 2000; ++n) mm::runner::playStep(o, &run);
    if (!sim.marble().position.allFinite()) std::abort();
  } catch (const mm::runner::UsageError& e) {
    if (std::string(e.what()).size() < 10) std::abort();  // a refusal says why
  }
  return 0;
}
