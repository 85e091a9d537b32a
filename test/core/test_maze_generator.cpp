// Procedural mazes: the same spec gives the same maze, every one is solvable, its holes keep off
// the path, and a bad spec is refused naming the key.
#include <gtest/gtest.h>

#include <string>

#include "marble_maze/maze_file.h"
#include "marble_maze/maze_generator.h"
#include "marble_maze/route_planner.h"

namespace marble_maze {
namespace {

TEST(MazeGenerator, TheSameSpecGivesTheSameMazeAndAnotherSeedAnother) {
  const std::string a = generatedMazeText("generated:seed=7,cells=9x7");
  EXPECT_EQ(a, generatedMazeText("generated:seed=7,cells=9x7"));
  EXPECT_NE(a, generatedMazeText("generated:seed=8,cells=9x7"));
  const Scene scene = loadScene("generated:seed=7,cells=9x7");
  EXPECT_EQ(scene.maze.size().x(), 19);
  EXPECT_EQ(scene.maze.size().y(), 15);
  EXPECT_EQ(scene.maze.goals().size(), 1u);
}

TEST(MazeGenerator, EveryMazeIsSolvableAndItsHolesKeepOffThePath) {
  int holes = 0;
  for (int seed = 0; seed < 50; ++seed)
    for (const char* cells : {"2x2", "5x5", "9x7", "20x3"}) {
      const std::string name =
          "generated:seed=" + std::to_string(seed) + ",cells=" + cells + ",holes=1";
      const Scene scene = loadScene(name);
      const RoutePlanner planner(scene.maze, scene.params.marble_radius);
      const Route route = planner.plan(planner.centre(scene.maze.start()));
      ASSERT_TRUE(route.found()) << name;
      for (const Maze::Cell& c : route.columns) EXPECT_FALSE(scene.maze.isHole(c)) << name;
      holes += static_cast<int>(scene.maze.holes().size());
    }
  EXPECT_GT(holes, 500);  // every dead end off the path a hole, at holes=1
}

TEST(MazeGenerator, ABadSpecIsRefusedNamingTheKey) {
  const std::pair<const char*, const char*> cases[] = {
      {"generated:seed=-1", "seed: expected a whole number"},
      {"generated:cells=1x5", "cells: expected WxH"},
      {"generated:cells=9", "cells: expected WxH"},
      {"generated:holes=2", "holes: expected a share from 0 to 1"},
      {"generated:size=3", "unknown key 'size' (known: seed, cells, holes)"},
  };
  for (const auto& [spec, message] : cases) {
    try {
      loadScene(spec);
      ADD_FAILURE() << spec << " was taken";
    } catch (const MazeFileError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace marble_maze
