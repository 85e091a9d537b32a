#include "marble_maze/maze_generator.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <queue>
#include <sstream>
#include <vector>

#include "marble_maze/in_quotes.h"
#include "marble_maze/maze_file.h"
#include "marble_maze/params.h"

namespace marble_maze {

namespace {

constexpr char kPrefix[] = "generated:";

struct Spec {
  std::uint64_t seed = 0;
  int width = 9, height = 7;
  double holes = 0.3;
};

/// SplitMix64, a number at a time: the same sequence from the same seed everywhere.
struct Random {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t x = (state += 0x9e3779b97f4a7c15ull);
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
  }
  int below(int n) { return static_cast<int>(next() % static_cast<std::uint64_t>(n)); }
  double unit() { return static_cast<double>(next() >> 11) * 0x1p-53; }
};

Spec parseSpec(const std::string& name) {
  const auto refuse = [&](const std::string& why) { return MazeFileError(name, 0, 0, why); };
  Spec spec;
  std::istringstream fields(name.substr(sizeof kPrefix - 1));
  for (std::string field; std::getline(fields, field, ',');) {
    const auto eq = field.find('=');
    const std::string key = field.substr(0, eq),
                      value = eq == field.npos ? "" : field.substr(eq + 1);
    double number = 0;
    if (key == "seed") {
      char* end = nullptr;
      spec.seed = std::strtoull(value.c_str(), &end, 10);
      if (value.empty() || *end != '\0' || value[0] == '-')
        throw refuse("seed: expected a whole number, got " + inQuotes(value));
    } else if (key == "cells") {
      const auto x = value.find('x');
      double w = 0, h = 0;
      if (x == value.npos || !parseFiniteNumber(value.substr(0, x), &w) ||
          !parseFiniteNumber(value.substr(x + 1), &h) || w != static_cast<int>(w) ||
          h != static_cast<int>(h) || w < 2 || h < 2 || w > 60 || h > 60)
        throw refuse("cells: expected WxH, each a whole number from 2 to 60, got " +
                     inQuotes(value));
      spec.width = static_cast<int>(w);
      spec.height = static_cast<int>(h);
    } else if (key == "holes") {
      if (!parseFiniteNumber(value, &number) || number < 0 || number > 1)
        throw refuse("holes: expected a share from 0 to 1, got " + inQuotes(value));
      spec.holes = number;
    } else {
      throw refuse("unknown key " + inQuotes(key) + " (known: seed, cells, holes)");
    }
  }
  return spec;
}

}  // namespace

bool isGeneratedMazeName(const std::string& name) {
  return name.rfind(kPrefix, 0) == 0;
}

std::string generatedMazeText(const std::string& name) {
  const Spec spec = parseSpec(name);
  const int w = spec.width, h = spec.height, cells = w * h;
  Random random{spec.seed};
  // A perfect maze by a depth-first walk from the start (cell 0, at the board's -x -y corner):
  // open[c * 2 + 0] is the wall to c's +x neighbour gone, open[c * 2 + 1] to its +y one.
  std::vector<bool> open(static_cast<std::size_t>(cells) * 2, false), seen(cells, false);
  std::vector<int> stack{0};
  seen[0] = true;
  while (!stack.empty()) {
    const int c = stack.back(), i = c % w, j = c / w;
    int choices[4], count = 0;
    if (i + 1 < w && !seen[c + 1]) choices[count++] = c + 1;
    if (i > 0 && !seen[c - 1]) choices[count++] = c - 1;
    if (j + 1 < h && !seen[c + w]) choices[count++] = c + w;
    if (j > 0 && !seen[c - w]) choices[count++] = c - w;
    if (count == 0) {
      stack.pop_back();
      continue;
    }
    const int n = choices[random.below(count)];
    const int low = std::min(c, n);
    open[static_cast<std::size_t>(low) * 2 + (std::abs(n - c) == 1 ? 0 : 1)] = true;
    seen[n] = true;
    stack.push_back(n);
  }
  // The goal is the cell farthest along the maze from the start; the path between them stays
  // free of holes.
  const auto neighbours = [&](int c) {
    std::vector<int> out;
    const int i = c % w, j = c / w;
    if (i + 1 < w && open[static_cast<std::size_t>(c) * 2]) out.push_back(c + 1);
    if (i > 0 && open[static_cast<std::size_t>(c - 1) * 2]) out.push_back(c - 1);
    if (j + 1 < h && open[static_cast<std::size_t>(c) * 2 + 1]) out.push_back(c + w);
    if (j > 0 && open[static_cast<std::size_t>(c - w) * 2 + 1]) out.push_back(c - w);
    return out;
  };
  std::vector<int> from(cells, -1), depth(cells, -1);
  std::queue<int> queue;
  queue.push(0);
  depth[0] = 0;
  int goal = 0;
  while (!queue.empty()) {
    const int c = queue.front();
    queue.pop();
    if (depth[c] > depth[goal]) goal = c;
    for (int n : neighbours(c))
      if (depth[n] < 0) {
        depth[n] = depth[c] + 1;
        from[n] = c;
        queue.push(n);
      }
  }
  std::vector<bool> on_path(cells, false);
  for (int c = goal; c >= 0; c = from[c]) on_path[c] = true;
  std::vector<bool> hole(cells, false);
  for (int c = 0; c < cells; ++c)
    if (!on_path[c] && neighbours(c).size() == 1 && random.unit() < spec.holes) hole[c] = true;

  // The plan: posts at even slots, walls between them, cells at odd slots; the top line is the
  // largest y.
  std::ostringstream text;
  text << "# " << name << "\nname: \"" << name << "\""
       << "\ngrid:\n  x: [0.005, 0.0221]\n  y: [0.005, 0.02325]\n  z: [0.005, 0.012]\n"
       << "layout: |\n";
  for (int row = 2 * h; row >= 0; --row) {
    text << "  ";
    for (int col = 0; col <= 2 * w; ++col) {
      const int i = col / 2, j = row / 2;
      char ch = ' ';
      if (row % 2 == 0 && col % 2 == 0) {
        ch = '+';
      } else if (row % 2 == 0) {  // a wall along x, below cell (i, j)
        const bool edge = row == 0 || row == 2 * h;
        ch = edge || !open[static_cast<std::size_t>((j - 1) * w + i) * 2 + 1] ? '-' : ' ';
      } else if (col % 2 == 0) {  // a wall along y, left of cell (i, j)
        const bool edge = col == 0 || col == 2 * w;
        ch = edge || !open[static_cast<std::size_t>(j * w + i - 1) * 2] ? '|' : ' ';
      } else {
        const int c = j * w + i;
        ch = c == 0 ? 'S' : c == goal ? 'G' : hole[c] ? 'O' : ' ';
      }
      text << ch;
    }
    text << "\n";
  }
  return text.str();
}

}  // namespace marble_maze
