#include "maze_node.h"

#include <tf2_eigen/tf2_eigen.h>
#include <visualization_msgs/MarkerArray.h>

#include <cmath>
#include <iomanip>
#include <set>
#include <sstream>

#include "marble_maze/MarbleState.h"
#include "marble_maze/MazeEvent.h"
#include "maze_description.h"
#include "maze_markers.h"

namespace marble_maze_ros {
namespace mm = marble_maze;

namespace {

// At most this much simulated time (or five timer periods, if longer) is caught up in one
// callback; a longer stall (a suspended process, a jump of the clock) is skipped with a warning
// rather than replayed in a burst.
constexpr double kMaxCatchUp = 1.0;  // s

/// A parameter's value as the text the core's parameter table reads ("0.7", "rolling",
/// "0.1,0,0.006"); throws naming the parameter when it has no such form.
std::string asText(XmlRpc::XmlRpcValue value, const std::string& name) {
  std::ostringstream out;
  out << std::setprecision(17);
  switch (value.getType()) {
    case XmlRpc::XmlRpcValue::TypeDouble:
      out << static_cast<double>(value);
      return out.str();
    case XmlRpc::XmlRpcValue::TypeInt:
      return std::to_string(static_cast<int>(value));
    case XmlRpc::XmlRpcValue::TypeBoolean:
      return static_cast<bool>(value) ? "true" : "false";
    case XmlRpc::XmlRpcValue::TypeString:
      return static_cast<std::string>(value);
    case XmlRpc::XmlRpcValue::TypeArray:
      for (int i = 0; i < value.size(); ++i)
        out << (i ? "," : "") << asText(value[i], name + "[" + std::to_string(i) + "]");
      return out.str();
    default:
      throw std::runtime_error(name + ": expected a number, a string or a list of numbers");
  }
}

double readRate(const ros::NodeHandle& pnh, const std::string& key, double fallback, double min,
                double max) {
  XmlRpc::XmlRpcValue value;
  if (!pnh.getParam(key, value)) return fallback;
  const std::string name = pnh.resolveName(key);
  double number = 0;
  if (!mm::parseFiniteNumber(asText(value, name), &number))
    throw std::runtime_error(name + ": expected a number");
  if (number < min || number > max) {
    std::ostringstream msg;
    msg << name << ": " << number << " is out of range [" << min << ", " << max << "]";
    throw std::runtime_error(msg.str());
  }
  return number;
}

std::string readText(const ros::NodeHandle& pnh, const std::string& key,
                     const std::string& fallback) {
  XmlRpc::XmlRpcValue value;
  if (!pnh.getParam(key, value)) return fallback;
  if (value.getType() != XmlRpc::XmlRpcValue::TypeString)
    throw std::runtime_error(pnh.resolveName(key) + ": expected a string");
  return static_cast<std::string>(value);
}

}  // namespace

MazeNode::Settings MazeNode::readSettings(const ros::NodeHandle& pnh, mm::Scene* scene) {
  // Every private parameter must be one we know: a misspelt one would otherwise do nothing.
  const std::set<std::string> node_keys = {"maze",        "update_rate",  "publish_rate",
                                           "marker_rate", "tilt_timeout", "auto_reset",
                                           "world_frame", "board_frame",  "marble_frame"};
  std::set<std::string> known = node_keys;
  for (const mm::ParamInfo& info : mm::paramInfos()) known.insert(info.key);
  std::vector<std::string> names;
  ros::param::getParamNames(names);
  const std::string prefix = pnh.getNamespace() + "/";
  for (const std::string& name : names) {
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string key =
        name.substr(prefix.size(), name.find('/', prefix.size()) - prefix.size());
    if (!known.count(key)) throw std::runtime_error(name + ": unknown parameter");
  }

  Settings s;
  s.maze = readText(pnh, "maze", s.maze);
  s.update_rate = readRate(pnh, "update_rate", s.update_rate, 1.0, 10000.0);
  s.publish_rate = readRate(pnh, "publish_rate", s.publish_rate, 0.1, 1000.0);
  s.marker_rate = readRate(pnh, "marker_rate", s.marker_rate, 0.1, 1000.0);
  s.tilt_timeout = readRate(pnh, "tilt_timeout", s.tilt_timeout, 0.0, 1e6);
  s.auto_reset = readRate(pnh, "auto_reset", s.auto_reset, 0.0, 1e6);
  s.world_frame = readText(pnh, "world_frame", s.world_frame);
  s.board_frame = readText(pnh, "board_frame", s.board_frame);
  s.marble_frame = readText(pnh, "marble_frame", s.marble_frame);

  try {
    *scene = mm::loadScene(s.maze);
  } catch (const mm::MazeFileError& e) {
    throw std::runtime_error(pnh.resolveName("maze") + ": " + e.what());
  }
  // The core's keys, as the runner's --set takes them.
  for (const mm::ParamInfo& info : mm::paramInfos()) {
    XmlRpc::XmlRpcValue value;
    if (!pnh.getParam(info.key, value)) continue;
    try {
      mm::setParam(scene->params, info.key, asText(value, pnh.resolveName(info.key)));
    } catch (const mm::ParamError& e) {
      throw std::runtime_error(prefix + e.what());
    }
  }
  try {
    mm::validate(scene->params);
  } catch (const mm::ParamError& e) {
    throw std::runtime_error(prefix + e.what());
  }
  return s;
}

MazeNode::MazeNode(ros::NodeHandle nh, ros::NodeHandle pnh) {
  mm::Scene scene;
  settings_ = readSettings(pnh, &scene);
  sim_ = std::make_unique<mm::Simulation>(scene);

  state_pub_ = nh.advertise<marble_maze::MarbleState>("marble_state", 10);
  event_pub_ = nh.advertise<marble_maze::MazeEvent>("events", 100);
  maze_pub_ = nh.advertise<marble_maze::MazeDescription>("maze", 1, true);
  maze_markers_pub_ = nh.advertise<visualization_msgs::MarkerArray>("maze_markers", 1, true);
  live_markers_pub_ = nh.advertise<visualization_msgs::MarkerArray>("live_markers", 1);
  marble_marker_pub_ = nh.advertise<visualization_msgs::Marker>("marble_marker", 10);
  const auto hints = ros::TransportHints().tcpNoDelay();
  tilt_sub_ = nh.subscribe("tilt", 100, &MazeNode::onTilt, this, hints);
  tilt_rate_sub_ = nh.subscribe("tilt_rate", 100, &MazeNode::onTiltRate, this, hints);
  reset_srv_ = nh.advertiseService("reset", &MazeNode::onReset, this);
  pause_srv_ = nh.advertiseService("pause", &MazeNode::onPause, this);
  resume_srv_ = nh.advertiseService("resume", &MazeNode::onResume, this);
  maze_pub_.publish(describe({sim_->maze(), sim_->params()}, settings_.board_frame));
  maze_markers_pub_.publish(mazeMarkers(sim_->maze(), settings_.board_frame));
  timer_ = nh.createTimer(ros::Duration(1.0 / settings_.update_rate), &MazeNode::onTimer, this);

  const mm::Params& p = sim_->params();
  ROS_INFO(
      "marble_maze: maze '%s' (%d x %d x %d tiles), model %s, integrator %s, step %g s x %d "
      "substeps",
      sim_->maze().name().c_str(), sim_->maze().size().x(), sim_->maze().size().y(),
      sim_->maze().size().z(), mm::getParam(p, "model").c_str(),
      mm::getParam(p, "integrator").c_str(), p.step, p.substeps);
}

ros::Time MazeNode::stampOfStep(std::uint64_t step) const {
  return stampOfTime(static_cast<double>(step) * sim_->params().step);
}

ros::Time MazeNode::stampOfTime(double sim_time) const {
  return origin_ +
         ros::Duration(sim_time - static_cast<double>(anchor_step_) * sim_->params().step);
}

void MazeNode::anchor(const ros::Time& now) {
  origin_ = now;
  anchor_step_ = sim_->steps();
}

void MazeNode::onTilt(const marble_maze::BoardTilt::ConstPtr& msg) {
  const char* topic = tilt_sub_.getTopic().c_str();
  if (!std::isfinite(msg->roll) || !std::isfinite(msg->pitch)) {
    ROS_WARN_THROTTLE(1.0, "%s: refused roll=%g pitch=%g (not finite); the board keeps its tilt",
                      topic, msg->roll, msg->pitch);
    return;
  }
  const double limit = sim_->params().tilt_limit;
  if (std::abs(msg->roll) > limit || std::abs(msg->pitch) > limit)
    ROS_WARN_THROTTLE(1.0, "%s: roll=%g pitch=%g rad beyond tilt_limit %g rad; clamped", topic,
                      msg->roll, msg->pitch, limit);
  queue(msg->header, {0, TiltCommand::Kind::Angles, msg->roll, msg->pitch});
}

void MazeNode::onTiltRate(const marble_maze::BoardTiltRate::ConstPtr& msg) {
  const char* topic = tilt_rate_sub_.getTopic().c_str();
  if (!std::isfinite(msg->roll_rate) || !std::isfinite(msg->pitch_rate)) {
    ROS_WARN_THROTTLE(1.0, "%s: refused roll_rate=%g pitch_rate=%g (not finite); nothing changed",
                      topic, msg->roll_rate, msg->pitch_rate);
    return;
  }
  const double limit = sim_->params().tilt_rate_limit;
  if (limit > 0 && (std::abs(msg->roll_rate) > limit || std::abs(msg->pitch_rate) > limit))
    ROS_WARN_THROTTLE(1.0,
                      "%s: roll_rate=%g pitch_rate=%g rad/s beyond tilt_rate_limit %g; clamped",
                      topic, msg->roll_rate, msg->pitch_rate, limit);
  queue(msg->header, {0, TiltCommand::Kind::Rates, msg->roll_rate, msg->pitch_rate});
}

void MazeNode::queue(const std_msgs::Header& header, TiltCommand command) {
  const ros::Time now = ros::Time::now();
  command.stamp = (header.stamp.isZero() ? now : header.stamp).toSec();
  last_command_ = now;
  levelled_after_timeout_ = false;
  if (!commands_.push(command))
    ROS_WARN_THROTTLE(1.0,
                      "tilt commands stamped far ahead fill the queue; dropped the one furthest "
                      "ahead");
}

void MazeNode::apply(const TiltCommand& command) {
  if (command.kind == TiltCommand::Kind::Angles)
    sim_->setTargetTilt(command.roll, command.pitch);
  else
    sim_->setTiltRate(command.roll, command.pitch);
}

void MazeNode::onTimer(const ros::TimerEvent&) {
  const ros::Time now = ros::Time::now();
  if (now.isZero()) return;  // a simulated clock that has not started
  if (origin_.isZero()) {    // the first tick of a running clock
    anchor(now);
    publish(true);
    return;
  }
  const ros::Time sim_now = stampOfStep(sim_->steps());
  // Steps are only ever taken up to now (give or take the rounding of a stamp to nanoseconds):
  // a clock behind the last step went back.
  if (now + ros::Duration(0.5 * sim_->params().step) < sim_now) {
    ROS_WARN("ROS time went back by %.3f s (a bag looping? a restarted clock?); following it",
             (sim_now - now).toSec());
    anchor(now);
    commands_.clear();
    if (!last_command_.isZero()) last_command_ = now;
    if (!finished_at_.isZero()) finished_at_ = now;
    last_state_stamp_ = last_marker_stamp_ = ros::Time();
    publish(true);
    return;
  }
  if (paused_) return;
  if (settings_.tilt_timeout > 0 && !levelled_after_timeout_ && !last_command_.isZero() &&
      (now - last_command_).toSec() > settings_.tilt_timeout) {
    ROS_INFO("no tilt command for %g s: levelling the board", settings_.tilt_timeout);
    sim_->setTargetTilt(0, 0);
    levelled_after_timeout_ = true;
  }
  stepUntil(now);
  publish(false);
}

void MazeNode::stepUntil(const ros::Time& now) {
  const double step = sim_->params().step;
  const auto stepped = static_cast<std::int64_t>(sim_->steps() - anchor_step_);
  auto due = static_cast<std::int64_t>(std::floor((now - origin_).toSec() / step + 1e-9)) - stepped;
  const double most_time = std::max(kMaxCatchUp, 5.0 / settings_.update_rate);
  const auto most = static_cast<std::int64_t>(most_time / step);
  if (due > most) {
    ROS_WARN_THROTTLE(5.0, "simulation fell %.3f s behind ROS time; skipping ahead",
                      (due - most) * step);
    origin_ += ros::Duration((due - most) * step);
    due = most;
  }
  for (std::int64_t i = 0; i < due; ++i) {
    commands_.applyDue(stampOfStep(sim_->steps()).toSec(),
                       [this](const TiltCommand& c) { apply(c); });
    sim_->step();
    publishEvents();
  }
  if (sim_->marble().phase == mm::MarblePhase::Free) return;
  if (finished_at_.isZero()) finished_at_ = now;
  if (settings_.auto_reset > 0 && (now - finished_at_).toSec() >= settings_.auto_reset) {
    sim_->reset();
    finished_at_ = ros::Time();
  }
}

void MazeNode::publishEvents() {
  for (const mm::Event& e : sim_->events()) {
    marble_maze::MazeEvent msg;
    msg.header.stamp = stampOfTime(e.time);
    msg.header.frame_id = settings_.board_frame;
    switch (e.kind) {
      case mm::EventKind::Collision:
        msg.kind = marble_maze::MazeEvent::COLLISION;
        break;
      case mm::EventKind::Hole:
        msg.kind = marble_maze::MazeEvent::HOLE;
        break;
      case mm::EventKind::Goal:
        msg.kind = marble_maze::MazeEvent::GOAL;
        break;
      case mm::EventKind::OffBoard:
        msg.kind = marble_maze::MazeEvent::OFF_BOARD;
        break;
    }
    msg.tile_x = e.tile.x();
    msg.tile_y = e.tile.y();
    msg.tile_z = e.tile.z();
    msg.impact_speed = e.speed;
    event_pub_.publish(msg);
    if (e.kind != mm::EventKind::Collision)
      ROS_INFO("t=%.3f s: %s at tile (%d, %d, %d)", e.time, mm::toString(e.kind).c_str(),
               e.tile.x(), e.tile.y(), e.tile.z());
  }
}

void MazeNode::publish(bool force) {
  const ros::Time stamp = stampOfStep(sim_->steps());
  // Each frame's stamps strictly increase: only a new step is published.
  const bool new_step = stamp > last_state_stamp_ || (force && last_state_stamp_.isZero());
  if (new_step && (force || (stamp - last_state_stamp_).toSec() >=
                                1.0 / settings_.publish_rate - 0.5 * sim_->params().step)) {
    last_state_stamp_ = stamp;
    const mm::Marble& m = sim_->marble();
    const mm::Mat3& board = sim_->board().rotation();
    const mm::Vec3 in_board = sim_->marbleInBoard();

    Eigen::Isometry3d world_to_board = Eigen::Isometry3d::Identity();
    world_to_board.linear() = board;
    geometry_msgs::TransformStamped board_tf = tf2::eigenToTransform(world_to_board);
    board_tf.header.stamp = stamp;
    board_tf.header.frame_id = settings_.world_frame;
    board_tf.child_frame_id = settings_.board_frame;
    Eigen::Isometry3d board_to_marble = Eigen::Isometry3d::Identity();
    board_to_marble.translation() = in_board;
    board_to_marble.linear() = board.transpose() * m.orientation.toRotationMatrix();
    geometry_msgs::TransformStamped marble_tf = tf2::eigenToTransform(board_to_marble);
    marble_tf.header.stamp = stamp;
    marble_tf.header.frame_id = settings_.board_frame;
    marble_tf.child_frame_id = settings_.marble_frame;
    tf_.sendTransform({board_tf, marble_tf});

    marble_maze::MarbleState state;
    state.header.stamp = stamp;
    state.header.frame_id = settings_.world_frame;
    state.position = tf2::toMsg(m.position);
    tf2::toMsg(m.velocity, state.velocity);
    tf2::toMsg(m.angular_velocity, state.angular_velocity);
    state.position_in_board = tf2::toMsg(in_board);
    state.roll = sim_->board().roll();
    state.pitch = sim_->board().pitch();
    state.contacts = static_cast<std::uint8_t>(std::min(m.contacts, 255));
    state.in_hole = m.phase == mm::MarblePhase::InHole;
    state.at_goal = m.phase == mm::MarblePhase::AtGoal;
    state.off_board = m.phase == mm::MarblePhase::OffBoard;
    state_pub_.publish(state);
  }
  if (stamp > last_marker_stamp_ &&
      (force || (stamp - last_marker_stamp_).toSec() >=
                    1.0 / settings_.marker_rate - 0.5 * sim_->params().step)) {
    last_marker_stamp_ = stamp;
    visualization_msgs::Marker marble =
        marbleMarker(sim_->params().marble_radius, settings_.marble_frame);
    marble.header.stamp = stamp;
    marble_marker_pub_.publish(marble);
    // The trail: the last 3 s at the marker rate; a jump (a reset, a place) starts a new one.
    const mm::Vec3 here = sim_->marbleInBoard();
    if (!trail_.empty() && (trail_.back() - here).norm() > 0.05) trail_.clear();
    trail_.push_back(here);
    while (trail_.size() > 3 * settings_.marker_rate) trail_.pop_front();
    visualization_msgs::MarkerArray live =
        liveMarkers(sim_->maze(), {trail_.begin(), trail_.end()}, sim_->params().marble_radius,
                    sim_->board().roll(), sim_->board().pitch(), settings_.board_frame);
    for (auto& m : live.markers) m.header.stamp = stamp;
    live_markers_pub_.publish(live);
  }
}

bool MazeNode::onReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  sim_->reset();
  commands_.clear();
  finished_at_ = ros::Time();
  res.success = true;
  res.message = "marble back at the start, board at its initial tilt";
  return true;
}

bool MazeNode::onPause(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  if (!paused_) {
    paused_ = true;
    paused_at_ = ros::Time::now();
  }
  res.success = true;
  res.message = "paused";
  return true;
}

bool MazeNode::onResume(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  if (paused_) {
    paused_ = false;
    // The simulation takes up where it stopped: the paused time is not simulated, nor does it
    // count towards the tilt timeout or the auto reset.
    const ros::Duration paused = ros::Time::now() - paused_at_;
    origin_ += paused;
    if (!last_command_.isZero()) last_command_ += paused;
    if (!finished_at_.isZero()) finished_at_ += paused;
  }
  res.success = true;
  res.message = "running";
  return true;
}

}  // namespace marble_maze_ros
