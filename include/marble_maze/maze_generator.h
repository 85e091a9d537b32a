// Procedural mazes from a seed: "generated:seed=7,cells=9x7,holes=0.3" wherever a maze is named
// (the runner's --maze, the node's ~maze and load_maze, marble_maze.agents' maze=). A perfect
// maze (one path between any two cells), its goal the cell farthest from the start, and holes in
// dead ends off that path, so that every maze it makes is solvable. The same spec gives the same
// maze file's text, bit for bit, on any machine.
#pragma once

#include <string>

namespace marble_maze {

/// Whether `name` asks for a generated maze ("generated:...").
bool isGeneratedMazeName(const std::string& name);

/// The maze file's text (doc/maze_format.md) of a generated maze. The spec's keys: seed (a whole
/// number, default 0), cells (WxH, each 2 to 60, default 9x7), holes (the share of the dead ends
/// off the path that are holes, 0 to 1, default 0.3). Throws MazeFileError naming a bad key.
std::string generatedMazeText(const std::string& name);

}  // namespace marble_maze
