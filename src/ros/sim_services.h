// The services programs and agents call: reset, pause, resume, step, place_marble, load_maze.
// Each refuses bad arguments and calls at the wrong moment with success false and a message that
// names the problem; the node then runs on as before.
#pragma once

#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include <cstdint>
#include <functional>
#include <string>
#include <utility>

#include "marble_maze/LoadMaze.h"
#include "marble_maze/MarbleState.h"
#include "marble_maze/PlaceMarble.h"
#include "marble_maze/Step.h"
#include "marble_maze/geometry.h"

namespace marble_maze_ros {

/// What the services do, given by the node. Each returns "" when done, or why not.
struct SimControl {
  std::function<std::string()> reset, pause, resume;
  std::function<std::string(std::uint32_t steps, marble_maze::MarbleState* after)> step;
  std::function<std::string(const marble_maze::Vec3& position_in_board,
                            const marble_maze::Vec3& velocity, const marble_maze::Vec3& spin)>
      place;
  std::function<std::string(const std::string& maze)> load;
};

class SimServices {
 public:
  explicit SimServices(SimControl control) : control_(std::move(control)) {}
  /// Offers the services under `nh`'s namespace.
  void advertise(ros::NodeHandle& nh);

  // What each call answers (callable without a master).
  bool onReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool onPause(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool onResume(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool onStep(marble_maze::Step::Request& req, marble_maze::Step::Response& res);
  bool onPlace(marble_maze::PlaceMarble::Request& req, marble_maze::PlaceMarble::Response& res);
  bool onLoad(marble_maze::LoadMaze::Request& req, marble_maze::LoadMaze::Response& res);

 private:
  SimControl control_;
  ros::ServiceServer reset_, pause_, resume_, step_, place_, load_;
};

}  // namespace marble_maze_ros
