#include "sim_services.h"

#include "marble_maze/in_quotes.h"
#include "marble_maze/maze_file.h"

namespace marble_maze_ros {
namespace mm = marble_maze;

namespace {

/// success and message from what a control said: "" is done.
template <typename Response>
bool answer(const std::string& why_not, const std::string& service, const std::string& done,
            Response* res) {
  res->success = why_not.empty();
  res->message = why_not.empty() ? done : service + ": " + why_not;
  if (!why_not.empty()) ROS_WARN("%s", res->message.c_str());
  return true;
}

mm::Vec3 vec(const geometry_msgs::Vector3& v) {
  return {v.x, v.y, v.z};
}

}  // namespace

void SimServices::advertise(ros::NodeHandle& nh) {
  reset_ = nh.advertiseService("reset", &SimServices::onReset, this);
  pause_ = nh.advertiseService("pause", &SimServices::onPause, this);
  resume_ = nh.advertiseService("resume", &SimServices::onResume, this);
  step_ = nh.advertiseService("step", &SimServices::onStep, this);
  place_ = nh.advertiseService("place_marble", &SimServices::onPlace, this);
  load_ = nh.advertiseService("load_maze", &SimServices::onLoad, this);
}

bool SimServices::onReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  return answer(control_.reset(), "reset", "marble back at the start, board at its initial tilt",
                &res);
}

bool SimServices::onPause(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  return answer(control_.pause(), "pause", "paused", &res);
}

bool SimServices::onResume(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  return answer(control_.resume(), "resume", "running", &res);
}

bool SimServices::onStep(marble_maze::Step::Request& req, marble_maze::Step::Response& res) {
  const std::string why =
      req.steps == 0 ? "steps: expected at least 1, got 0" : control_.step(req.steps, &res.state);
  return answer(why, "step", "advanced " + std::to_string(req.steps) + " steps", &res);
}

bool SimServices::onPlace(marble_maze::PlaceMarble::Request& req,
                          marble_maze::PlaceMarble::Response& res) {
  const mm::Vec3 position(req.position.x, req.position.y, req.position.z);
  return answer(control_.place(position, vec(req.velocity), vec(req.angular_velocity)),
                "place_marble", "placed", &res);
}

bool SimServices::onLoad(marble_maze::LoadMaze::Request& req,
                         marble_maze::LoadMaze::Response& res) {
  const std::string why = req.maze.empty() ? "maze: empty; expected a built-in maze's name (" +
                                                 mm::embeddedSceneList() + ") or a maze file's path"
                                           : control_.load(req.maze);
  return answer(why, "load_maze", "loaded " + mm::inQuotes(req.maze), &res);
}

}  // namespace marble_maze_ros
