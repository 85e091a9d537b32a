// The ROS layer's translations, without a ROS master: the clock's mapping, the maze's message,
// the markers, a recording re-simulated.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "../../src/ros/maze_description.h"
#include "../../src/ros/maze_markers.h"
#include "../../src/ros/recording.h"
#include "../../src/ros/seq_gaps.h"
#include "../../src/ros/sim_clock.h"
#include "marble_maze/maze_file.h"

namespace marble_maze_ros {
namespace {
namespace mm = marble_maze;

TEST(SimClock, StepsHaveExactStampsAndCommandsTakeTheFirstStepAtOrAfterTheirStamp) {
  SimClock clock;
  clock.anchor(ros::Time(100.0), 2000, 2.0, 1000000);  // step 2000 starts at ROS 100 s; 1 ms steps
  EXPECT_EQ(clock.stampOfStep(2500), ros::Time(100.5));
  EXPECT_EQ(clock.stampOfStep(2000 + 1000000).toNSec(), ros::Time(1100.0).toNSec());  // exact
  EXPECT_EQ(clock.stepAt(ros::Time(100.0025), 2000), 2003u);
  EXPECT_EQ(clock.stepAt(ros::Time(100.003), 2000), 2003u);  // exactly a step's start
  EXPECT_EQ(clock.stepAt(ros::Time(99.0), 2000), 2000u);     // past: the next step
  EXPECT_EQ(clock.stepsDue(ros::Time(101.0005)), 3000u);
  EXPECT_EQ(onGrid(ros::Time(5, 1234567), 1000000).toNSec(), ros::Time(5, 1000000).toNSec());
  EXPECT_EQ(onGrid(ros::Time(5, 1234567), 1000000, true).toNSec(), ros::Time(5, 2000000).toNSec());
}

/// Feeds `seqs` from one source; returns the messages they show lost, all told.
std::uint64_t lostIn(SeqGaps* gaps, const std::vector<std::uint32_t>& seqs,
                     const std::string& source = "/tilt /agent") {
  std::uint64_t lost = 0;
  for (std::uint32_t seq : seqs) lost += gaps->take(source, seq);
  return lost;
}

/// `count` seqs from `first` on, one after another.
std::vector<std::uint32_t> run(std::uint32_t first, std::uint32_t count) {
  std::vector<std::uint32_t> seqs(count);
  for (std::uint32_t i = 0; i < count; ++i) seqs[i] = first + i;
  return seqs;
}

std::vector<std::uint32_t> operator+(std::vector<std::uint32_t> a,
                                     const std::vector<std::uint32_t>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

TEST(SeqGaps, CountsAGapOnceTheSeriesBeforeItHasStayedQuiet) {
  SeqGaps gaps;
  // 10..19, then 40 on: 20 lost, told by the kQuiet-th message after 40, not before.
  EXPECT_EQ(lostIn(&gaps, run(10, 10) + run(40, SeqGaps::kQuiet)), 0u);
  EXPECT_EQ(lostIn(&gaps, run(40 + SeqGaps::kQuiet, 1)), 20u);
  // Two more gaps of 5 and 7 in one series, each told once.
  SeqGaps more;
  EXPECT_EQ(lostIn(&more, run(0, 10) + run(15, 10) + run(32, 3 * SeqGaps::kQuiet)), 12u);
  // Nothing lost: nothing told.
  SeqGaps none;
  EXPECT_EQ(lostIn(&none, run(7, 1000)), 0u);
}

TEST(SeqGaps, TwoPublishersUnderOneNameAreNoLoss) {
  // rosbag play sends two recorded agents' commands under its own name, with their seqs: one
  // at 10, the other at 500, interleaved one by one and in bursts of up to 50.
  for (std::uint32_t burst : {1u, 7u, 50u}) {
    SeqGaps gaps;
    std::vector<std::uint32_t> seqs;
    for (std::uint32_t i = 0; i < 20; ++i)
      seqs = seqs + run(500 + i * burst, burst) + run(10 + i * burst, burst);
    EXPECT_EQ(lostIn(&gaps, seqs + run(10 + 20 * burst, 3 * SeqGaps::kQuiet)), 0u) << burst;
  }
  // The other publisher going on on the very message the gap is judged at.
  SeqGaps judged;
  EXPECT_EQ(lostIn(&judged, run(10, 10) + run(500, SeqGaps::kQuiet) + run(20, 5) +
                                run(600, 2 * SeqGaps::kQuiet)),
            0u);
  // Three, and one of them losing 30 of its own: those are told.
  SeqGaps gaps;
  std::vector<std::uint32_t> seqs;
  for (std::uint32_t i = 0; i < 300; ++i) {
    const std::uint32_t skip = i >= 100 ? 30 : 0;
    seqs = seqs + run(1000 + i, 1) + run(10 + i + skip, 1) + run(5000 + i, 1);
  }
  EXPECT_EQ(lostIn(&gaps, seqs), 30u);
}

TEST(SeqGaps, ALoopOrARestartIsNoLossAndMemoryStaysBounded) {
  SeqGaps gaps;
  // rosbag play -l: the same seqs again; a publisher restarted: from 0.
  EXPECT_EQ(lostIn(&gaps, run(100, 300) + run(100, 300) + run(0, 300)), 0u);
  // A publisher that leaves seq at 0.
  EXPECT_EQ(lostIn(&gaps, std::vector<std::uint32_t>(500, 0)), 0u);
  // Many publishers come and go (rostopic pub, each with a new name): a bounded number kept.
  for (int i = 0; i < 1000; ++i) gaps.take("/tilt /rostopic_" + std::to_string(i), 0);
  EXPECT_LE(gaps.sources(), SeqGaps::kMostSources);
  // A gap is still told after that.
  EXPECT_EQ(lostIn(&gaps, run(0, 10) + run(20, 2 * SeqGaps::kQuiet), "/tilt /late"), 10u);
}

/// A session on a scene recorded from its state now, at 100 s, without inputs yet (what a bag of
/// record.launch holds, without the bag).
Recording recordingFrom(const mm::Scene& scene, const mm::Session& session) {
  Recording r;
  r.scene.maze_text = scene.text;
  r.scene.maze_source = scene.source;
  r.scene.params = mm::paramsText(scene.params);
  r.snapshot.header.stamp = ros::Time(100);
  r.snapshot.state = session.save();
  r.snapshot.params = r.scene.params;
  r.snapshot.anchor_stamp = ros::Time(100);
  return r;
}

/// A session on the classic maze from its start, recorded with one input: a load of the
/// prototype at step 10.
Recording recordingWithALoad() {
  const mm::Scene classic = mm::loadScene("classic"), prototype = mm::loadScene("prototype");
  Recording r = recordingFrom(classic, mm::Session(classic));
  marble_maze::SimInput load;
  load.kind = marble_maze::SimInput::LOAD;
  load.index = 0;
  load.step = 10;
  load.header.stamp = ros::Time(100.01);
  load.maze_text = prototype.text;
  load.maze_source = prototype.source;
  load.params = mm::paramsText(prototype.params);
  r.inputs.push_back(load);
  return r;
}

TEST(Replayer, ARecordedLoadRefusingParametersSetOverTheRecordingSaysWhichAndWhy) {
  const Recording recording = recordingWithALoad();
  Replayer plain(recording);
  for (int k = 0; k < 10; ++k) {
    plain.applyDue();
    plain.step();
  }
  ASSERT_EQ(plain.applyDue().size(), 1u);
  EXPECT_EQ(plain.session().simulation().maze().name(), mm::loadScene("prototype").maze.name());
  // A radius the classic start takes and the prototype's does not (0.0105 m): the re-run stops
  // at the load with a ParamError (simulate: exit status 2) naming the input and the cause.
  Replayer wider(recording, {{"marble_radius", "0.0105"}});
  for (int k = 0; k < 10; ++k) {
    wider.applyDue();
    wider.step();
  }
  try {
    wider.applyDue();
    ADD_FAILURE() << "the load took a marble too wide for the prototype's start";
  } catch (const mm::ParamError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("the maze load recorded as input 0 (at 100.01"), std::string::npos) << what;
    EXPECT_NE(what.find("marble_radius: a marble of radius 0.0105 m does not fit"),
              std::string::npos)
        << what;
  }
}

/// A session on the classic maze whose snapshot still holds a tilt command queued for step 4 (a
/// stamp 4 ms ahead), recorded with the command as the node logs it: an input at the step it
/// acted at.
Recording recordingWithAQueuedCommand() {
  const mm::Scene classic = mm::loadScene("classic");
  mm::Session session(classic);
  session.command({4, mm::TiltCommand::Kind::Angles, 0.1, -0.05, 0});
  Recording r = recordingFrom(classic, session);
  marble_maze::SimInput tilt;
  tilt.kind = marble_maze::SimInput::TILT;
  tilt.index = 0;
  tilt.step = 4;
  tilt.header.stamp = ros::Time(100.004);
  tilt.roll = 0.1;
  tilt.pitch = -0.05;
  r.inputs.push_back(tilt);
  return r;
}

TEST(Replayer, ACommandTheSnapshotHeldActsAtItsRecordedTimeUnderAnotherStep) {
  const Recording recording = recordingWithAQueuedCommand();
  ASSERT_EQ(mm::Session(mm::loadScene("classic")).simulation().params().step, 0.001);
  const auto tilt = [](Replayer& replay) {
    const mm::Board& board = replay.session().simulation().board();
    return std::abs(board.roll()) + std::abs(board.pitch());
  };
  const auto run = [](Replayer& replay, int steps) {
    for (int k = 0; k < steps; ++k) {
      replay.applyDue();
      replay.step();
    }
  };
  // The command acted at 4 ms: until then the board stays level, in 1 ms steps and in 0.5 ms
  // ones. (From the snapshot's queue, which counts steps, it acted at 2 ms under 0.5 ms steps.)
  Replayer recorded(recording), halved(recording, {{"step", "0.0005"}});
  run(recorded, 4);
  run(halved, 8);
  EXPECT_EQ(tilt(recorded), 0.0);
  EXPECT_EQ(tilt(halved), 0.0);
  // Then the board turns alike in both, at 10 ms within what the servo's rate limit leaves of
  // rounding where it takes over at another instant (microradians; a step early was 2 mrad).
  run(recorded, 6);
  run(halved, 12);
  const mm::Board& a = recorded.session().simulation().board();
  const mm::Board& b = halved.session().simulation().board();
  EXPECT_GT(tilt(recorded), 1e-3);  // the board turns: the comparison means something
  EXPECT_NEAR(a.roll(), b.roll(), 1e-5);
  EXPECT_NEAR(a.pitch(), b.pitch(), 1e-5);
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
