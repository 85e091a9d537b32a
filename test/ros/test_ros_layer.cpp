// The ROS layer's translations, without a ROS master: the command queue and the markers.
#include <gtest/gtest.h>

#include <set>

#include "../../src/ros/command_queue.h"
#include "../../src/ros/maze_markers.h"
#include "marble_maze/maze_file.h"

namespace marble_maze_ros {
namespace {

TEST(CommandQueue, AppliesCommandsInStampOrderWhenDue) {
  CommandQueue queue;
  queue.push({2.0, TiltCommand::Kind::Angles, 0.2, 0});
  queue.push({1.0, TiltCommand::Kind::Angles, 0.1, 0});
  queue.push({1.0, TiltCommand::Kind::Rates, 0.15, 0});  // same stamp: after the first
  queue.push({3.0, TiltCommand::Kind::Angles, 0.3, 0});
  std::vector<double> applied;
  queue.applyDue(2.0, [&](const TiltCommand& c) { applied.push_back(c.roll); });
  EXPECT_EQ(applied, (std::vector<double>{0.1, 0.15, 0.2}));
  EXPECT_EQ(queue.size(), 1u);
  queue.applyDue(2.5, [&](const TiltCommand& c) { applied.push_back(c.roll); });
  EXPECT_EQ(queue.size(), 1u);  // the 3 s command waits for its time
}

TEST(CommandQueue, WhenFullDropsTheCommandStampedFurthestAhead) {
  CommandQueue queue;
  for (int i = 0; i < 10000; ++i) EXPECT_TRUE(queue.push({1.0 + i, TiltCommand::Kind::Angles}));
  EXPECT_FALSE(queue.push({0.5, TiltCommand::Kind::Angles, 0.5, 0}));
  EXPECT_EQ(queue.size(), 10000u);
  std::vector<double> first;
  queue.applyDue(1.0, [&](const TiltCommand& c) { first.push_back(c.stamp); });
  EXPECT_EQ(first, (std::vector<double>{0.5, 1.0}));  // the most urgent one was kept
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
