// The node's three time policies without a ROS master: each driven as its timers drive it, over
// a real session of the classic maze, with ROS time set by hand.
#include <gtest/gtest.h>
#include <ros/time.h>

#include <vector>

#include "follow_ros_time.h"
#include "lockstep.h"
#include "marble_maze/maze_file.h"
#include "own_clock.h"

namespace marble_maze_ros {
namespace {

namespace mm = marble_maze;

/// What the node does for a policy, recorded: the states published (their stamps), the anchors
/// and the restarts.
struct FakeNode {
  explicit FakeNode(double step = 0.001) : session(sceneWithStep(step)) {
    ros::Time::setNow(ros::Time(100.0));
  }
  static mm::Scene sceneWithStep(double step) {
    mm::Scene scene = mm::loadScene("classic");
    scene.params.step = step;
    return scene;
  }

  PolicyContext context() {
    PolicyContext c;
    c.session = &session;
    c.clock = &clock;
    c.settings = &settings;
    c.run_steps = [this](std::uint64_t count, bool publish_each) {
      for (std::uint64_t i = 0; i < count; ++i) {
        session.run(1);
        if (publish_each) each_step_published += 1;
      }
    };
    c.publish_state = [this](const ros::Time& stamp, bool) { published.push_back(stamp); };
    c.reanchor = [this](const ros::Time& origin) {
      clock.anchor(origin, session.steps(), session.simulation().time(),
                   std::llround(session.simulation().params().step * 1e9));
    };
    c.restart = [this](const ros::Time& now) {
      clock.anchor(now, session.steps(), session.simulation().time(), 1000000);
      session.reset();
      ++restarts;
    };
    return c;
  }

  mm::Session session;
  SimClock clock;
  NodeSettings settings;
  std::vector<ros::Time> published;
  int each_step_published = 0;
  int restarts = 0;
};

TEST(FollowRosTime, TheStepsDueAreTheRosTimeElapsedOnAGridOfSteps) {
  FakeNode node;
  FollowRosTime policy(node.context());
  ros::Time::setNow(ros::Time(100.0005));
  policy.tick(ros::Time::now());  // the first tick anchors on the step grid: 100.000 s
  EXPECT_EQ(node.clock.origin(), ros::Time(100.0));
  EXPECT_EQ(node.session.steps(), 0u);
  policy.tick(ros::Time(100.1));
  EXPECT_EQ(node.session.steps(), 100u);
  EXPECT_EQ(node.each_step_published, 100);  // each step's state, when due
  EXPECT_EQ(policy.stateStamp(), ros::Time(100.1));
}

TEST(FollowRosTime, AStallIsCaughtUpASecondAtMostAndTheRestSkipped) {
  FakeNode node;
  FollowRosTime policy(node.context());
  policy.tick(ros::Time(100.0));
  policy.tick(ros::Time(110.0));  // ten seconds later
  EXPECT_EQ(node.session.steps(), 1000u);
  HealthFigures f;
  policy.fillHealth(&f);
  EXPECT_EQ(f.skipped_steps, 9000u);
  EXPECT_TRUE(f.follows_ros_time);
  EXPECT_EQ(policy.stateStamp(), ros::Time(110.0));  // the steps taken end at now
}

TEST(FollowRosTime, AClockThatGoesBackRestartsTheSession) {
  FakeNode node;
  FollowRosTime policy(node.context());
  policy.tick(ros::Time(100.0));
  policy.tick(ros::Time(100.5));
  policy.tick(ros::Time(50.0));
  EXPECT_EQ(node.restarts, 1);
  EXPECT_EQ(node.clock.origin(), ros::Time(50.0));
}

TEST(FollowRosTime, PausedNoStepIsTakenAndTheFrozenStateTakesTheTimeThatPasses) {
  FakeNode node;
  FollowRosTime policy(node.context());
  policy.tick(ros::Time(100.0));
  node.session.pause();
  policy.paused();
  ros::Time::setNow(ros::Time(101.0));
  policy.tick(ros::Time::now());
  EXPECT_EQ(node.session.steps(), 0u);
  ASSERT_FALSE(node.published.empty());
  EXPECT_EQ(node.published.back(), ros::Time(101.0));
}

TEST(FollowRosTime, PausedTheFrozenStateComesAtThePublishRateUnderATimerThatTicksLate) {
  FakeNode node;
  node.settings.publish_rate = 50;
  FollowRosTime policy(node.context());
  policy.tick(ros::Time(100.0));
  node.session.pause();
  policy.paused();
  const std::size_t before = node.published.size();
  // Ticks every 3 ms, each 0 to 2 ms late: 10 s of them.
  for (int k = 1; k <= 3334; ++k) {
    ros::Time::setNow(ros::Time(100.0 + 0.003 * k + 0.001 * (k % 3)));
    policy.tick(ros::Time::now());
  }
  // 50 a second, 500 in 10 s (to one: where the first falls), not one a period plus a tick.
  EXPECT_NEAR(static_cast<double>(node.published.size() - before), 500, 1);
}

TEST(FollowRosTime, ACommandActsAtTheStepItsStampFallsOn) {
  FakeNode node;
  FollowRosTime policy(node.context());
  policy.tick(ros::Time(100.0));
  const double held = policy.command(ros::Time(100.05), mm::TiltCommand::Kind::Angles, 0.0, 0.05);
  EXPECT_DOUBLE_EQ(held, 0.05);
  policy.tick(ros::Time(100.049));
  EXPECT_EQ(node.session.queued(), 1u);  // held until its step
  EXPECT_EQ(node.session.simulation().board().pitch(), 0.0);
  policy.tick(ros::Time(100.1));
  EXPECT_EQ(node.session.queued(), 0u);
  EXPECT_GT(node.session.simulation().board().pitch(), 0.0);
}

TEST(Lockstep, EachCommandAdvancesOnePeriodAndPublishesOnce) {
  FakeNode node;
  node.settings.lockstep = 0.02;
  Lockstep policy(node.context());
  node.context().reanchor(ros::Time(0));
  policy.command(ros::Time(), mm::TiltCommand::Kind::Angles, 0.0, 0.05);
  EXPECT_EQ(node.session.steps(), 20u);
  EXPECT_EQ(node.each_step_published, 0);  // not a state a step: one a period
  ASSERT_EQ(node.published.size(), 1u);
  EXPECT_EQ(node.published.back(), ros::Time(0.02));
  EXPECT_GT(node.session.simulation().board().pitch(), 0.0);  // the command in force
}

TEST(Lockstep, PausedACommandWaitsAndARefusedOneIsAnsweredAtTheSameStamp) {
  FakeNode node;
  node.settings.lockstep = 0.02;
  Lockstep policy(node.context());
  node.context().reanchor(ros::Time(0));
  policy.refused();
  ASSERT_EQ(node.published.size(), 1u);
  EXPECT_EQ(node.published.back(), ros::Time(0));
  node.session.pause();
  policy.command(ros::Time(), mm::TiltCommand::Kind::Angles, 0.0, 0.05);
  EXPECT_EQ(node.session.steps(), 0u);
  EXPECT_EQ(node.session.queued(), 1u);
  EXPECT_EQ(node.published.size(), 1u);  // paused, no state comes
}

TEST(Lockstep, A55HzPeriodIsHonouredExactly) {
  // The node's step is shortened to divide the period (fitToLockstep): 19 steps of 0.957 ms.
  FakeNode node(mm::stepDividing(1.0 / 55, 0.001));
  node.settings.lockstep = 1.0 / 55;  // 18.18 ms
  Lockstep policy(node.context());
  EXPECT_EQ(policy.stepsPerPeriod(), 19u);
  for (int k = 0; k < 55; ++k) policy.command(ros::Time(), mm::TiltCommand::Kind::Angles, 0, 0);
  EXPECT_NEAR(node.session.simulation().time(), 1.0, 1e-12);
  HealthFigures f;
  policy.fillHealth(&f);
  EXPECT_EQ(f.running, "running in lockstep: each tilt command advances one period");
  EXPECT_EQ(f.aimed_factor, 0);  // no rate to fall behind
  EXPECT_FALSE(f.follows_ros_time);
}

TEST(OwnClock, AtARealTimeFactorItRunsThatManyTimesTheWallTime) {
  FakeNode node;
  node.settings.own_clock = true;
  node.settings.real_time_factor = 20;
  OwnClock policy(node.context());
  node.context().reanchor(ros::Time(0));
  policy.realTimeFactorChanged();  // aims from now
  const ros::WallTime begin = ros::WallTime::now();
  policy.tick(begin + ros::WallDuration(0.04));
  EXPECT_NEAR(static_cast<double>(node.session.steps()), 800, 1);  // 0.8 s in 0.04 s
  // Far behind (a stall of a wall second): a second caught up at most, the rest skipped.
  policy.tick(begin + ros::WallDuration(1.04));
  EXPECT_NEAR(static_cast<double>(node.session.steps()), 1800, 1);
  HealthFigures behind;
  policy.fillHealth(&behind);
  EXPECT_NEAR(static_cast<double>(behind.skipped_steps), 19000, 2);
  node.session.pause();
  const std::uint64_t paused_at = node.session.steps();
  policy.tick(ros::WallTime::now() + ros::WallDuration(0.2));
  EXPECT_EQ(node.session.steps(), paused_at);  // its clock stands
  HealthFigures f;
  policy.fillHealth(&f);
  EXPECT_EQ(f.aimed_factor, 20);
}

TEST(OwnClock, RunFreeItStepsInSlicesOfWallTime) {
  FakeNode node;
  node.settings.own_clock = true;
  OwnClock policy(node.context());
  node.context().reanchor(ros::Time(0));
  policy.tick(ros::WallTime::now());
  EXPECT_GE(node.session.steps(), 100u);  // at least one run of 100 in its 5 ms slice
  EXPECT_EQ(node.session.steps() % 100, 0u);
}

}  // namespace
}  // namespace marble_maze_ros

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::Time::init();
  return RUN_ALL_TESTS();
}
