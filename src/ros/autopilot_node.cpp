// autopilot: plays the maze from ROS alone, as another node would. It reads the latched `maze`
// and `marble_state`, plans a route to a goal around walls and holes, and steers the marble along
// it by publishing `tilt` at ~rate (55 Hz, as the real game's motors are driven), within the
// tilt limit. It draws its route on `autopilot_route` (a marker in the board frame) and says what
// it does on `~status` (latched: playing, reached the goal, fell in, no route). When the marble
// is reset after a hole or the goal it plans and plays again; where no route exists it says so,
// levels the board and stops playing until the marble is elsewhere (reset, put, a new maze).
// Parameters: ~rate (Hz, 55), ~max_speed (m/s along the route, 0.1), ~start_delay (s of wall
// time before it first steers, 1: a new publisher's first messages are lost to subscribers that
// have not connected yet, a recorder among them).
#include <ros/ros.h>
#include <std_msgs/String.h>
#include <visualization_msgs/Marker.h>

#include <cstdarg>
#include <cstdio>
#include <memory>

#include "marble_maze/BoardTilt.h"
#include "marble_maze/MarbleState.h"
#include "marble_maze/MazeDescription.h"
#include "marble_maze/autopilot.h"
#include "marble_maze/board.h"
#include "maze_description.h"
#include "maze_markers.h"
#include "node_settings.h"
#include "run_node.h"

namespace {
namespace mm = marble_maze;

class AutopilotNode {
 public:
  AutopilotNode(ros::NodeHandle nh, ros::NodeHandle pnh) {
    rate_ = marble_maze_ros::readNumber(pnh, "rate", 55.0, 0.1, 1000);
    max_speed_ = marble_maze_ros::readNumber(pnh, "max_speed", 0.1, 1e-3, 10);
    const double delay = marble_maze_ros::readNumber(pnh, "start_delay", 1.0, 0, 3600);
    start_after_ = ros::WallTime::now() + ros::WallDuration(delay);
    tilt_pub_ = nh.advertise<mm::BoardTilt>("tilt", 10);
    route_pub_ = nh.advertise<visualization_msgs::Marker>("autopilot_route", 1, true);
    status_pub_ = pnh.advertise<std_msgs::String>("status", 1, true);
    maze_sub_ = nh.subscribe("maze", 1, &AutopilotNode::onMaze, this);
    state_sub_ = nh.subscribe("marble_state", 10, &AutopilotNode::onState, this);
    timer_ = nh.createTimer(ros::Duration(1.0 / rate_), &AutopilotNode::onTimer, this);
  }

 private:
  void onMaze(const mm::MazeDescription::ConstPtr& msg) {
    mm::Scene scene;
    try {
      scene = marble_maze_ros::sceneOf(*msg);
    } catch (const std::exception& e) {
      ROS_ERROR("autopilot: %s", e.what());
      return;
    }
    mm::AutopilotSettings settings;
    settings.tilt_limit = scene.params.tilt_limit;
    settings.acceleration_per_tilt =
        (scene.params.model == mm::Model::Rolling ? 5.0 / 7.0 : 1.0) * scene.params.gravity;
    settings.max_speed = max_speed_;
    settings.lead = scene.params.tilt_response_time;
    // The same maze again with other physics (a reconfigure): it steers on along its route.
    const bool same_board = pilot_ && maze_ && sameBoard(*maze_, *msg);
    scene_ = scene;
    maze_ = msg;
    if (same_board) {
      pilot_->setSettings(settings);
      ROS_INFO("autopilot: maze '%s' with new physics", msg->name.c_str());
      return;
    }
    pilot_ = std::make_unique<mm::Autopilot>(scene_.maze, scene_.params.marble_radius, settings);
    board_frame_ = msg->header.frame_id;
    playing_ = false;
    stuck_ = false;
    ROS_INFO("autopilot: maze '%s'", msg->name.c_str());
  }

  /// Whether two descriptions are of the same board and marble: the route stands.
  static bool sameBoard(const mm::MazeDescription& a, const mm::MazeDescription& b) {
    return a.header.frame_id == b.header.frame_id && a.name == b.name &&
           a.thin_width == b.thin_width && a.wide_width == b.wide_width && a.slots == b.slots &&
           a.solid == b.solid && a.pivot == b.pivot && a.start == b.start && a.goals == b.goals &&
           a.holes == b.holes && a.marble_radius == b.marble_radius;
  }

  void onState(const mm::MarbleState::ConstPtr& msg) { state_ = msg; }

  void onTimer(const ros::TimerEvent&) {
    if (!pilot_ || !state_ || ros::WallTime::now() < start_after_) return;
    const mm::MarbleState& s = *state_;
    const bool finished = s.in_hole || s.at_goal || s.off_board;
    if (finished) {
      if (playing_) finish(s);
      stuck_ = false;  // a reset gives it another go
      return;
    }
    mm::Observation seen;
    seen.position = mm::Vec2(s.position_in_board.x, s.position_in_board.y);
    // Stuck where no route starts, it tries again once the marble is elsewhere: put there, or
    // on a new maze's start (a state of the old maze can come after the new maze did).
    if (stuck_ && (seen.position - stuck_at_).norm() < scene_.params.marble_radius) return;
    stuck_ = false;
    if (!playing_ && !start(s, seen.position)) return;
    // The velocity in the board frame: the world's, turned back by the board's tilt.
    const mm::Vec3 velocity = mm::Board::rotationFor(s.roll, s.pitch).transpose() *
                              mm::Vec3(s.velocity.x, s.velocity.y, s.velocity.z);
    seen.velocity = velocity.head<2>();
    seen.tilt = {s.roll, s.pitch};
    // How old the state is: on a busy machine a period or more, which the steering allows for.
    seen.age = (ros::Time::now() - s.header.stamp).toSec();
    const std::size_t waypoints = pilot_->route().waypoints.size();
    const mm::Tilt tilt = pilot_->steer(seen);
    if (pilot_->route().waypoints.size() != waypoints) publishRoute();  // planned again
    publishTilt(tilt.roll, tilt.pitch);
  }

  bool start(const mm::MarbleState& s, const mm::Vec2& position) {
    if (!pilot_->plan(position)) {
      say(ros::console::levels::Error,
          "no route with room for the marble from (%.3f, %.3f) m in the board frame to a goal of "
          "maze '%s': stopped",
          position.x(), position.y(), scene_.maze.name().c_str());
      publishTilt(0, 0);
      stuck_ = true;
      stuck_at_ = position;
      return false;
    }
    playing_ = true;
    started_ = s.header.stamp;
    say(ros::console::levels::Info, "playing: a route of %zu waypoints from (%.3f, %.3f) m",
        pilot_->route().waypoints.size(), position.x(), position.y());
    publishRoute();
    return true;
  }

  void finish(const mm::MarbleState& s) {
    playing_ = false;
    const double took = (s.header.stamp - started_).toSec();
    if (s.at_goal)
      say(ros::console::levels::Info, "reached the goal in %.2f s from the start of its route",
          took);
    else
      say(ros::console::levels::Warn, "the marble %s %.2f s into its route",
          s.in_hole ? "fell into a hole" : "left the board", took);
    publishTilt(0, 0);
  }

  /// Logs a line and puts it on ~status.
  void say(ros::console::levels::Level level, const char* format, ...) {
    char text[512];
    va_list args;
    va_start(args, format);
    std::vsnprintf(text, sizeof text, format, args);
    va_end(args);
    ROS_LOG(level, ROSCONSOLE_DEFAULT_NAME, "autopilot: %s", text);
    std_msgs::String status;
    status.data = text;
    status_pub_.publish(status);
  }

  void publishTilt(double roll, double pitch) {
    mm::BoardTilt msg;
    msg.header.stamp = ros::Time::now();
    msg.roll = roll;
    msg.pitch = pitch;
    tilt_pub_.publish(msg);
  }

  void publishRoute() {
    visualization_msgs::Marker m = marble_maze_ros::lockedMarker(
        board_frame_, "autopilot_route", 0, visualization_msgs::Marker::LINE_STRIP);
    m.scale.x = 0.0015;  // m, the line's width
    m.color =
        marble_maze_ros::colour(0.25f, 0.65f, 1.0f, 0.8f);  // light blue: the marble is orange
    for (const mm::Vec2& w : pilot_->route().waypoints) {
      geometry_msgs::Point p;
      p.x = w.x();
      p.y = w.y();
      p.z = 0.001;  // just above the floor
      m.points.push_back(p);
    }
    route_pub_.publish(m);
  }

  double rate_ = 55, max_speed_ = 0.1;
  ros::WallTime start_after_;
  mm::Scene scene_;
  mm::MazeDescription::ConstPtr maze_;  // the last one taken
  std::unique_ptr<mm::Autopilot> pilot_;
  std::string board_frame_ = "board";
  mm::MarbleState::ConstPtr state_;
  bool playing_ = false;
  bool stuck_ = false;  // no route from stuck_at_: waits for the marble to be elsewhere
  mm::Vec2 stuck_at_ = mm::Vec2::Zero();
  ros::Time started_;
  ros::Publisher tilt_pub_, route_pub_, status_pub_;
  ros::Subscriber maze_sub_, state_sub_;
  ros::Timer timer_;
};

}  // namespace

int main(int argc, char** argv) {
  return marble_maze_ros::runNode<AutopilotNode>(argc, argv, "autopilot");
}
