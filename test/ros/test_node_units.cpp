// The node's units that translate to and from ROS, without a ROS master: the tilt commands'
// screening, the state's messages and transforms, the services' answers and dynamic_reconfigure.
#include <gtest/gtest.h>
#include <tf2_eigen/tf2_eigen.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include "../../src/ros/frames.h"
#include "../../src/ros/reconfigure.h"
#include "../../src/ros/sim_services.h"
#include "../../src/ros/state_messages.h"
#include "../../src/ros/tilt_input.h"
#include "marble_maze/maze_file.h"
#include "marble_maze/simulation.h"

namespace marble_maze_ros {
namespace {
namespace mm = marble_maze;
using Kind = mm::TiltCommand::Kind;

bool says(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(TiltInput, RefusesACommandThatIsNotFiniteNamingTheField) {
  const mm::Params limits;
  const Screened angles =
      screenCommand(Kind::Angles, std::numeric_limits<double>::quiet_NaN(), 0.0, limits);
  EXPECT_TRUE(angles.refused);
  EXPECT_TRUE(says(angles.warning, "roll=nan")) << angles.warning;
  EXPECT_TRUE(says(angles.warning, "(not finite); the board keeps its tilt")) << angles.warning;
  const Screened rates =
      screenCommand(Kind::Rates, 0.0, -std::numeric_limits<double>::infinity(), limits);
  EXPECT_TRUE(rates.refused);
  EXPECT_TRUE(says(rates.warning, "pitch_rate=-inf")) << rates.warning;
}

TEST(TiltInput, PassesACommandBeyondTheLimitWithAWarningAndOneWithinSilently) {
  mm::Params limits;
  limits.tilt_limit = 0.1;
  limits.tilt_rate_limit = 2.0;
  const Screened beyond = screenCommand(Kind::Angles, 0.0, -0.3, limits);
  EXPECT_FALSE(beyond.refused);
  EXPECT_EQ(beyond.warning, "roll=0 pitch=-0.3 rad beyond tilt_limit 0.1; clamped");
  const Screened fast = screenCommand(Kind::Rates, 2.5, 0.0, limits);
  EXPECT_FALSE(fast.refused);
  EXPECT_EQ(fast.warning, "roll_rate=2.5 pitch_rate=0 rad/s beyond tilt_rate_limit 2; clamped");
  EXPECT_EQ(screenCommand(Kind::Angles, 0.1, -0.1, limits).warning, "");  // at the limit: within
  limits.tilt_rate_limit = 0;                                             // no rate limit
  EXPECT_EQ(screenCommand(Kind::Rates, 100.0, 0.0, limits).warning, "");
}

/// The classic maze a moment into a tilt: the board turned, the marble rolling.
mm::Simulation rolling() {
  mm::Simulation sim(mm::loadScene("classic"));
  sim.setTargetTilt(0.08, -0.05);
  sim.placeMarble(sim.startInBoard(), mm::Vec3(0.05, 0.02, 0.0));
  for (int i = 0; i < 100; ++i) sim.step();
  return sim;
}

TEST(StateMessages, TheTransformsComposeToTheStatesWorldPosition) {
  const mm::Simulation sim = rolling();
  ASSERT_GT(sim.marble().velocity.norm(), 0.01);  // the comparisons below mean something
  const Frames frames{"lab", "lab_board", "lab_marble"};
  const ros::Time stamp(12, 500);
  const marble_maze::MarbleState state = marbleStateMessage(sim, stamp, frames);
  EXPECT_EQ(state.header.frame_id, "lab");
  EXPECT_EQ(state.header.stamp, stamp);
  EXPECT_EQ(state.roll, sim.board().roll());
  EXPECT_EQ(state.pitch, sim.board().pitch());
  EXPECT_FALSE(state.in_hole || state.at_goal || state.off_board);

  const auto tfs = boardAndMarbleTransforms(sim, stamp, frames);
  EXPECT_EQ(tfs[0].header.frame_id, "lab");
  EXPECT_EQ(tfs[0].child_frame_id, "lab_board");
  EXPECT_EQ(tfs[1].header.frame_id, "lab_board");
  EXPECT_EQ(tfs[1].child_frame_id, "lab_marble");
  const Eigen::Isometry3d world_to_marble =
      tf2::transformToEigen(tfs[0]) * tf2::transformToEigen(tfs[1]);
  Eigen::Vector3d position;
  tf2::fromMsg(state.position, position);
  EXPECT_LT((world_to_marble.translation() - position).norm(), 1e-12);  // rounding only
  // The marble frame's orientation is the marble's own.
  const mm::Mat3 marble = sim.marble().orientation.toRotationMatrix();
  EXPECT_LT((world_to_marble.linear() - marble).norm(), 1e-12);
}

TEST(StateMessages, OdometryCarriesTheTwistInTheMarblesFrame) {
  const mm::Simulation sim = rolling();
  const nav_msgs::Odometry odom = odometryMessage(sim, ros::Time(3), Frames());
  EXPECT_EQ(odom.header.frame_id, "world");
  EXPECT_EQ(odom.child_frame_id, "marble");
  Eigen::Quaterniond orientation;
  tf2::fromMsg(odom.pose.pose.orientation, orientation);
  Eigen::Vector3d linear, angular;
  tf2::fromMsg(odom.twist.twist.linear, linear);
  tf2::fromMsg(odom.twist.twist.angular, angular);
  // Turned back into the world, the twist is the marble's velocity and spin.
  EXPECT_LT((orientation * linear - sim.marble().velocity).norm(), 1e-12);
  EXPECT_LT((orientation * angular - sim.marble().angular_velocity).norm(), 1e-12);
}

/// Controls that answer `why_not` and remember what they were given.
struct Recorder {
  std::string why_not;
  int calls = 0;
  mm::Vec3 position, velocity, spin;
  std::string maze;

  SimControl control() {
    SimControl c;
    c.reset = c.pause = c.resume = [this] {
      ++calls;
      return why_not;
    };
    c.step = [this](std::uint32_t, marble_maze::MarbleState*) {
      ++calls;
      return why_not;
    };
    c.place = [this](const mm::Vec3& p, const mm::Vec3& v, const mm::Vec3& w) {
      ++calls;
      position = p, velocity = v, spin = w;
      return why_not;
    };
    c.load = [this](const std::string& name) {
      ++calls;
      maze = name;
      return why_not;
    };
    return c;
  }
};

TEST(SimServices, RefusesZeroStepsAndAnEmptyMazeWithoutCallingTheNode) {
  Recorder node;
  SimServices services(node.control());
  marble_maze::Step::Request step;
  marble_maze::Step::Response stepped;
  step.steps = 0;
  EXPECT_TRUE(services.onStep(step, stepped));
  EXPECT_FALSE(stepped.success);
  EXPECT_EQ(stepped.message, "step: steps: expected at least 1, got 0");
  marble_maze::LoadMaze::Request load;
  marble_maze::LoadMaze::Response loaded;
  EXPECT_TRUE(services.onLoad(load, loaded));
  EXPECT_FALSE(loaded.success);
  EXPECT_TRUE(says(loaded.message, "load_maze: maze: empty")) << loaded.message;
  EXPECT_EQ(node.calls, 0);
}

TEST(SimServices, AnswersWithTheNodesReasonNamingTheService) {
  Recorder node;
  node.why_not = "already paused";
  SimServices services(node.control());
  std_srvs::Trigger::Request request;
  std_srvs::Trigger::Response response;
  EXPECT_TRUE(services.onPause(request, response));
  EXPECT_FALSE(response.success);
  EXPECT_EQ(response.message, "pause: already paused");
  node.why_not = "";
  EXPECT_TRUE(services.onReset(request, response));
  EXPECT_TRUE(response.success);
  EXPECT_EQ(response.message, "marble back at the start, board at its initial tilt");
  marble_maze::LoadMaze::Request load;
  marble_maze::LoadMaze::Response loaded;
  load.maze = "classic";
  EXPECT_TRUE(services.onLoad(load, loaded));
  EXPECT_TRUE(loaded.success);
  EXPECT_EQ(node.maze, "classic");
  EXPECT_EQ(node.calls, 3);  // pause, reset, load
}

TEST(SimServices, PlacesWithThePositionVelocityAndSpinInTheirPlaces) {
  Recorder node;
  SimServices services(node.control());
  marble_maze::PlaceMarble::Request place;
  marble_maze::PlaceMarble::Response placed;
  place.position.x = 0.01, place.position.y = -0.02, place.position.z = 0.006;
  place.velocity.x = 0.1, place.velocity.y = 0.2, place.velocity.z = 0.3;
  place.angular_velocity.x = 4, place.angular_velocity.y = 5, place.angular_velocity.z = 6;
  EXPECT_TRUE(services.onPlace(place, placed));
  EXPECT_TRUE(placed.success);
  EXPECT_EQ(node.position, mm::Vec3(0.01, -0.02, 0.006));
  EXPECT_EQ(node.velocity, mm::Vec3(0.1, 0.2, 0.3));
  EXPECT_EQ(node.spin, mm::Vec3(4, 5, 6));
}

/// A node's parameters as dynamic_reconfigure sees them: the core's defaults and one key of the
/// node's own, changed only when `why_not` is empty.
struct LiveValues {
  mm::Params params;
  double factor = 1;
  std::string why_not;
  std::vector<Reconfigure::Changes> applied;
  static mm::ParamInfo factorKey() {
    return {"factor", "", "a node's own number", mm::ParamInfo::Type::Number, 0, 100, {}, true};
  }

  Reconfigure reconfigure() {
    return Reconfigure(
        {factorKey()},
        [this](const Reconfigure::Changes& changes) {
          applied.push_back(changes);
          if (!why_not.empty()) return why_not;
          for (const auto& [key, value] : changes)
            key == "factor" ? void(factor = std::stod(value)) : mm::setParam(params, key, value);
          return std::string();
        },
        [this](const std::string& key) {
          return key == "factor" ? mm::exactText(factor) : mm::getParam(params, key);
        });
  }
};

/// A config's values by name, as text.
std::map<std::string, std::string> valuesOf(const dynamic_reconfigure::Config& c) {
  std::map<std::string, std::string> values;
  for (const auto& p : c.doubles) values[p.name] = mm::exactText(p.value);
  for (const auto& p : c.ints) values[p.name] = std::to_string(p.value);
  for (const auto& p : c.strs) values[p.name] = p.value;
  return values;
}

TEST(Reconfigure, DescribesEveryLiveKeyWithItsTypeRangeDefaultAndChoices) {
  LiveValues node;
  node.params.restitution = 0.7;  // the default is the value in force, not the table's
  const dynamic_reconfigure::ConfigDescription d = node.reconfigure().description();
  ASSERT_EQ(d.groups.size(), 1u);
  std::vector<mm::ParamInfo> live;
  for (const mm::ParamInfo& info : mm::paramInfos())
    if (info.live) live.push_back(info);
  live.push_back(LiveValues::factorKey());
  ASSERT_EQ(d.groups[0].parameters.size(), live.size());
  const auto min = valuesOf(d.min), max = valuesOf(d.max), dflt = valuesOf(d.dflt);
  int choices = 0;
  for (std::size_t i = 0; i < live.size(); ++i) {
    const mm::ParamInfo& info = live[i];
    const dynamic_reconfigure::ParamDescription& p = d.groups[0].parameters[i];
    EXPECT_EQ(p.name, info.key);
    const char* type = info.type == mm::ParamInfo::Type::Number  ? "double"
                       : info.type == mm::ParamInfo::Type::Whole ? "int"
                                                                 : "str";
    EXPECT_EQ(p.type, type) << info.key;
    EXPECT_TRUE(says(p.description, info.help)) << info.key;
    const std::string value = info.key == "factor" ? "1" : mm::getParam(node.params, info.key);
    EXPECT_EQ(dflt.at(info.key), value) << info.key;
    if (info.type == mm::ParamInfo::Type::Number) {
      EXPECT_EQ(min.at(info.key), mm::exactText(info.min)) << info.key;
      EXPECT_EQ(max.at(info.key), mm::exactText(info.max)) << info.key;
    }
    if (info.type == mm::ParamInfo::Type::Whole) {
      EXPECT_EQ(std::stod(min.at(info.key)), info.min) << info.key;
      EXPECT_EQ(std::stod(max.at(info.key)), info.max) << info.key;
    }
    for (const std::string& name : info.choices) {  // the GUI's drop-down, one entry a choice
      ++choices;
      EXPECT_TRUE(says(p.edit_method, "'name': '" + name + "'")) << p.edit_method;
    }
    EXPECT_EQ(p.edit_method.empty(), info.choices.empty()) << info.key;
  }
  EXPECT_EQ(dflt.at("restitution"), "0.7");
  EXPECT_GT(choices, 0);  // the model's and the integrator's names were seen
}

TEST(Reconfigure, AppliesOnlyWhatDiffersFromTheValuesInForce) {
  LiveValues node;
  Reconfigure reconfigure = node.reconfigure();
  dynamic_reconfigure::Reconfigure::Request request;
  dynamic_reconfigure::Reconfigure::Response response;
  request.config = reconfigure.description().dflt;  // a client sends every value
  EXPECT_TRUE(reconfigure.onSet(request, response));
  EXPECT_TRUE(node.applied.empty());
  for (auto& p : request.config.doubles)
    if (p.name == "restitution") p.value = 0.25;
  EXPECT_TRUE(reconfigure.onSet(request, response));
  ASSERT_EQ(node.applied.size(), 1u);
  EXPECT_EQ(node.applied[0], (Reconfigure::Changes{{"restitution", "0.25"}}));
  EXPECT_EQ(node.params.restitution, 0.25);
  EXPECT_EQ(valuesOf(response.config).at("restitution"), "0.25");
}

TEST(Reconfigure, ARefusedChangeAnswersWithTheValuesInForce) {
  LiveValues node;
  node.why_not = "restitution: 2 is out of range [0, 1]";
  Reconfigure reconfigure = node.reconfigure();
  dynamic_reconfigure::Reconfigure::Request request;
  dynamic_reconfigure::Reconfigure::Response response;
  dynamic_reconfigure::DoubleParameter restitution, factor;
  restitution.name = "restitution", restitution.value = 2;
  factor.name = "factor", factor.value = 4;
  request.config.doubles = {restitution, factor};
  dynamic_reconfigure::StrParameter unknown;  // not a live key: ignored, the rest considered
  unknown.name = "maze", unknown.value = "classic";
  request.config.strs = {unknown};
  EXPECT_TRUE(reconfigure.onSet(request, response));
  ASSERT_EQ(node.applied.size(), 1u);
  EXPECT_EQ(node.applied[0], (Reconfigure::Changes{{"restitution", "2"}, {"factor", "4"}}));
  const auto answered = valuesOf(response.config);
  EXPECT_EQ(answered.at("restitution"), mm::getParam(mm::Params(), "restitution"));
  EXPECT_EQ(answered.at("factor"), "1");
  EXPECT_EQ(answered.count("maze"), 0u);
}

TEST(Frames, ANamespaceGivesTheBoardAndTheMarbleItsNameAndSharesTheWorld) {
  const Frames root = framesIn("/");
  EXPECT_EQ((std::vector<std::string>{root.world, root.board, root.marble}),
            (std::vector<std::string>{"world", "board", "marble"}));
  const Frames nested = framesIn("/a/b");
  EXPECT_EQ((std::vector<std::string>{nested.world, nested.board, nested.marble}),
            (std::vector<std::string>{"world", "a/b/board", "a/b/marble"}));
  EXPECT_EQ(whyNotAChain(root), "");
  EXPECT_EQ(whyNotAChain(nested), "");
}

TEST(Frames, ABrokenChainIsRefusedNamingTheParameter) {
  const auto why = [](const std::string& world, const std::string& board,
                      const std::string& marble) {
    return whyNotAChain({world, board, marble});
  };
  EXPECT_EQ(why("", "board", "marble"), "world_frame: a frame needs a name");
  EXPECT_TRUE(says(why("world", "/board", "marble"), "board_frame: '/board' starts with '/'"));
  EXPECT_TRUE(says(why("world", "board", "my marble"), "marble_frame: 'my marble' holds a space"));
  EXPECT_TRUE(says(why("world", "board\t", "marble"), "board_frame:"));
  EXPECT_TRUE(says(why("world", "board", "board"), "marble_frame: 'board' is board_frame too"));
  EXPECT_EQ(why("welt", "brett/ü", "kugel"), "");  // any other character is a name's
}

TEST(Frames, FindsTheBoardOrTheMarbleInATfMessage) {
  const Frames frames = framesIn("/a");
  tf2_msgs::TFMessage message;
  message.transforms.resize(2);
  message.transforms[0].child_frame_id = "b/board";  // another namespace's
  message.transforms[1].child_frame_id = "marble";
  EXPECT_EQ(ownFrameIn(message, frames), "");
  message.transforms[1].child_frame_id = "a/marble";
  EXPECT_EQ(ownFrameIn(message, frames), "a/marble");
}

}  // namespace
}  // namespace marble_maze_ros
