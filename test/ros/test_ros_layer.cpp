// The ROS layer's translations, without a ROS master: the clock's mapping, the maze's message and
// the markers.
#include <gtest/gtest.h>

#include <set>

#include "../../src/ros/maze_description.h"
#include "../../src/ros/maze_markers.h"
#include "../../src/ros/sim_clock.h"
#include "marble_maze/maze_file.h"

namespace marble_maze_ros {
namespace {

TEST(SimClock, StampsFollowTheAnchorAndCommandsTakeTheNextStepAtOrAfterTheirStamp) {
  SimClock clock;
  clock.anchor(ros::Time(100.0), 2.0);  // simulated 2 s at ROS 100 s
  EXPECT_EQ(clock.stampOf(2.5), ros::Time(100.5));
  const double step = 0.001;
  // Now: step 2000 at 2 s. A stamp 2.5 ms ahead: step 2003 is the first to start at or after it.
  EXPECT_EQ(clock.stepAt(ros::Time(100.0025), 2000, 2.0, step), 2003u);
  EXPECT_EQ(clock.stepAt(ros::Time(100.003), 2000, 2.0, step), 2003u);  // exactly a step's start
  EXPECT_EQ(clock.stepAt(ros::Time(99.0), 2000, 2.0, step), 2000u);     // past: the next step
  EXPECT_NEAR(clock.due(ros::Time(101.0)), 3.0, 1e-9);
}

TEST(MazeDescription, DescribesTheMazeAndReadsBackTheSameMaze) {
  const marble_maze::Scene scene = marble_maze::loadScene("classic");
  const marble_maze::MazeDescription msg = describe(scene, "board");
  const marble_maze::Scene back = sceneOf(msg);
  EXPECT_EQ(back.maze.size(), scene.maze.size());
  for (int k = 0; k < scene.maze.size().z(); ++k)
    for (int j = 0; j < scene.maze.size().y(); ++j)
      for (int i = 0; i < scene.maze.size().x(); ++i)
        EXPECT_EQ(back.maze.solid({i, j, k}), scene.maze.solid({i, j, k}));
  EXPECT_TRUE(back.maze.start() == scene.maze.start());
  EXPECT_EQ(back.maze.goals().size(), scene.maze.goals().size());
  EXPECT_EQ(msg.holes.size(), scene.maze.holes().size());
  EXPECT_EQ(back.params.tilt_limit, scene.params.tilt_limit);
  marble_maze::MazeDescription broken = msg;
  broken.solid.pop_back();
  EXPECT_THROW(sceneOf(broken), std::runtime_error);
}

TEST(MazeMarkers, OneCubeListPerKindAndSizeWithStableIds) {
  const marble_maze::Scene scene = marble_maze::loadScene("classic");
  const auto a = mazeMarkers(scene.maze, "board");
  const auto b = mazeMarkers(scene.maze, "board");
  ASSERT_EQ(a.markers.size(), b.markers.size());
  std::set<std::string> namespaces;
  std::set<std::pair<std::string, int>> ids;
  std::size_t floor_cubes = 0;
  for (std::size_t i = 0; i < a.markers.size(); ++i) {
    const auto& m = a.markers[i];
    EXPECT_EQ(m.header.frame_id, "board");
    EXPECT_EQ(m.type, visualization_msgs::Marker::CUBE_LIST);
    EXPECT_TRUE(m.frame_locked);
    EXPECT_EQ(m.ns, b.markers[i].ns);
    EXPECT_EQ(m.id, b.markers[i].id);
    EXPECT_TRUE(ids.insert({m.ns, m.id}).second) << "duplicate " << m.ns << "/" << m.id;
    namespaces.insert(m.ns);
    if (m.ns == "floor") floor_cubes += m.points.size();
  }
  EXPECT_EQ(namespaces, (std::set<std::string>{"floor", "walls", "holes", "start", "goal"}));
  EXPECT_EQ(floor_cubes, 21u * 17u - 6u);  // every floor tile but the six holes
}

TEST(MazeMarkers, CubesSitOnTheTilesInTheBoardFrame) {
  const marble_maze::Scene scene = marble_maze::loadScene("classic");
  for (const auto& m : mazeMarkers(scene.maze, "board").markers) {
    if (m.ns != "floor") continue;
    for (const auto& p : m.points) {
      EXPECT_NEAR(p.z, -0.0025, 1e-12);  // the 5 mm slab's centre, below the pivot
      EXPECT_LE(std::abs(p.x), 0.138);
      EXPECT_LE(std::abs(p.y), 0.1155);
    }
  }
}

}  // namespace
}  // namespace marble_maze_ros
