#include "node_settings.h"

#include <algorithm>
#include <cstdio>
#include <iomanip>
#include <set>
#include <sstream>
#include <stdexcept>

#include "marble_maze/in_quotes.h"

namespace marble_maze_ros {
namespace mm = marble_maze;

namespace {

/// A parameter's value as the text the core's parameter table reads ("0.7", "rolling",
/// "0.1,0,0.006"; a list [0.1, 0, 0.006] is the same); throws naming the parameter when it has
/// no such form.
std::string asText(XmlRpc::XmlRpcValue value, const std::string& name) {
  switch (value.getType()) {
    case XmlRpc::XmlRpcValue::TypeDouble:
      return mm::exactText(static_cast<double>(value));
    case XmlRpc::XmlRpcValue::TypeInt:
      return std::to_string(static_cast<int>(value));
    case XmlRpc::XmlRpcValue::TypeBoolean:
      return static_cast<bool>(value) ? "true" : "false";
    case XmlRpc::XmlRpcValue::TypeString:
      return static_cast<std::string>(value);
    case XmlRpc::XmlRpcValue::TypeArray: {
      std::string text;
      for (int i = 0; i < value.size(); ++i)
        text += (i ? "," : "") + asText(value[i], name + "[" + std::to_string(i) + "]");
      return text;
    }
    default:
      throw std::runtime_error(name + ": expected a number, a string or a list of numbers");
  }
}

}  // namespace

double readNumber(const ros::NodeHandle& pnh, const std::string& key, double fallback, double min,
                  double max) {
  XmlRpc::XmlRpcValue value;
  if (!pnh.getParam(key, value)) return fallback;
  const std::string name = pnh.resolveName(key);
  double number = 0;
  const std::string text = asText(value, name);
  if (!mm::parseFiniteNumber(text, &number))
    throw std::runtime_error(name + ": " + mm::whyNotANumber(text));
  if (number < min || number > max)
    throw std::runtime_error(mm::outOfRangeText(name, number, min, max));
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

bool readFlag(const ros::NodeHandle& pnh, const std::string& key, bool fallback) {
  XmlRpc::XmlRpcValue value;
  if (!pnh.getParam(key, value)) return fallback;
  if (value.getType() != XmlRpc::XmlRpcValue::TypeBoolean)
    throw std::runtime_error(pnh.resolveName(key) + ": expected true or false");
  return static_cast<bool>(value);
}

namespace {

const std::set<std::string>& nodeKeys() {
  // (diagnostic_period is diagnostic_updater's own.)
  static const std::set<std::string> keys = {
      "maze",         "update_rate", "publish_rate",     "marker_rate",      "tilt_timeout",
      "rate_timeout", "auto_reset",  "world_frame",      "board_frame",      "marble_frame",
      "clock",        "lockstep",    "real_time_factor", "diagnostic_period"};
  return keys;
}

}  // namespace

Frames readFrames(const ros::NodeHandle& pnh) {
  Frames frames = framesIn(ros::names::parentNamespace(pnh.getNamespace()));
  frames.world = readText(pnh, "world_frame", frames.world);
  frames.board = readText(pnh, "board_frame", frames.board);
  frames.marble = readText(pnh, "marble_frame", frames.marble);
  const std::string why = whyNotAChain(frames);
  if (!why.empty()) throw std::runtime_error(pnh.getNamespace() + "/" + why);
  return frames;
}

void fitToLockstep(const NodeSettings& settings, mm::Params* params) {
  if (settings.lockstep > 0) params->step = mm::stepDividing(settings.lockstep, params->step);
}

mm::Scene sceneFor(const std::string& maze, const NodeSettings& settings) {
  mm::Scene scene = mm::loadScene(maze);
  for (const auto& [key, text] : settings.overrides) mm::overrideParam(&scene, key, text);
  fitToLockstep(settings, &scene.params);
  mm::validate(scene.params);
  return scene;
}

NodeSettings readSettings(const ros::NodeHandle& pnh, mm::Scene* scene) {
  // Every private parameter must be one we know: a misspelt one would otherwise do nothing.
  std::set<std::string> known = nodeKeys();
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

  NodeSettings s;
  s.maze = readText(pnh, "maze", s.maze);
  s.update_rate = readNumber(pnh, "update_rate", s.update_rate, 1.0, kMostUpdateRate);
  s.publish_rate = readNumber(pnh, "publish_rate", s.publish_rate, 0.1, 1e6);
  s.marker_rate = readNumber(pnh, "marker_rate", s.marker_rate, 0.1, 1e6);
  s.session.tilt_timeout = readNumber(pnh, "tilt_timeout", s.session.tilt_timeout, 0.0, 1e6);
  s.session.rate_timeout = readNumber(pnh, "rate_timeout", s.session.rate_timeout, 0.0, 1e6);
  s.session.auto_reset = readNumber(pnh, "auto_reset", s.session.auto_reset, 0.0, 1e6);
  s.frames = readFrames(pnh);
  s.own_clock = readFlag(pnh, "clock", s.own_clock);
  s.real_time_factor = readNumber(pnh, "real_time_factor", s.real_time_factor,
                                  realTimeFactorKey().min, realTimeFactorKey().max);
  if (!s.own_clock && pnh.hasParam("real_time_factor"))
    ROS_WARN("%s is used only with %s; ignored", pnh.resolveName("real_time_factor").c_str(),
             pnh.resolveName("clock").c_str());
  // (A period is taken in one callback: a longer one would hold the node up. The node also
  // bounds its count of steps, whatever the step.)
  s.lockstep = readNumber(pnh, "lockstep", s.lockstep, 0.0, 60.0);
  if (s.own_clock && s.lockstep > 0)
    throw std::runtime_error(pnh.resolveName("lockstep") + ": a lockstep node owns /clock too; " +
                             pnh.resolveName("clock") + " must not be set with it");

  // The core's keys, as the runner's --set takes them, in the table's order (a preset first).
  for (const mm::ParamInfo& info : mm::paramInfos()) {
    XmlRpc::XmlRpcValue value;
    if (pnh.getParam(info.key, value))
      s.overrides.emplace_back(info.key, asText(value, pnh.resolveName(info.key)));
  }
  try {
    *scene = sceneFor(s.maze, s);
  } catch (const mm::MazeFileError& e) {
    throw std::runtime_error(pnh.resolveName("maze") + ": " + e.what());
  } catch (const mm::ParamError& e) {
    throw std::runtime_error(prefix + e.what());
  }
  const std::string why = whyNotRunnable(s, scene->params);
  if (!why.empty()) throw std::runtime_error(prefix + why);
  return s;
}

std::string whyNotRunnable(const NodeSettings& settings, const mm::Params& params) {
  const std::string step = "step: " + mm::exactText(params.step) + " s makes ";
  std::string why =
      mm::whyTooMuchWork(settings.lockstep / params.step, params,
                         step + "~lockstep's " + mm::exactText(settings.lockstep) + " s");
  if (!why.empty()) return why;
  // Rates of simulated time: at most one message a step.
  const double per_second = 1.0 / params.step;
  for (const auto& [key, rate] :
       {std::pair<const char*, double>{"~publish_rate", settings.publish_rate},
        {"~marker_rate", settings.marker_rate}})
    if (rate > per_second * (1 + 1e-9))
      return step + mm::exactText(per_second) + " steps a second, fewer than " + key + "'s " +
             mm::exactText(rate) + " Hz";
  return "";
}

std::vector<std::string> writeBack(const ros::NodeHandle& pnh, const NodeSettings& s,
                                   const mm::Params& params) {
  std::vector<std::string> keys;
  const auto put = [&](const std::string& key, const auto& value) {
    pnh.setParam(key, value);
    keys.push_back(key);
  };
  put("maze", s.maze);
  put("update_rate", s.update_rate);
  put("publish_rate", s.publish_rate);
  put("marker_rate", s.marker_rate);
  put("tilt_timeout", s.session.tilt_timeout);
  put("rate_timeout", s.session.rate_timeout);
  put("auto_reset", s.session.auto_reset);
  put("world_frame", s.frames.world);
  put("board_frame", s.frames.board);
  put("marble_frame", s.frames.marble);
  put("clock", s.own_clock);
  put("real_time_factor", s.real_time_factor);
  put("lockstep", s.lockstep);
  for (const mm::ParamInfo& info : mm::paramInfos()) {
    if (info.key == "start_position" && !params.has_start_position) continue;  // the start cell
    const std::string text = mm::getParam(params, info.key);
    double number = 0;
    if (info.type == mm::ParamInfo::Type::Whole && mm::parseFiniteNumber(text, &number))
      put(info.key, static_cast<int>(number));
    else if (info.type == mm::ParamInfo::Type::Number && mm::parseFiniteNumber(text, &number))
      put(info.key, number);
    else
      put(info.key, text);
  }
  return keys;
}

const mm::ParamInfo& realTimeFactorKey() {
  static const mm::ParamInfo key{"real_time_factor",
                                 "",
                                 "with ~clock: times real time to run at, 0 = as fast as it can",
                                 mm::ParamInfo::Type::Number,
                                 0,
                                 1e6,
                                 {},
                                 true};
  return key;
}

double parseRealTimeFactor(const std::string& text) {
  const mm::ParamInfo& key = realTimeFactorKey();
  double value = 0;
  if (!mm::parseFiniteNumber(text, &value))
    throw mm::ParamError(key.key + ": " + mm::whyNotANumber(text));
  if (value < key.min || value > key.max)
    throw mm::ParamError(mm::outOfRangeText(key.key, value, key.min, key.max));
  return value;
}

WrittenBack::WrittenBack(const ros::NodeHandle& pnh) : pnh_(pnh) {
  any_given_ = ros::param::get(pnh.getNamespace(), given_);
}

WrittenBack::~WrittenBack() {
  // Only the keys it wrote: each back to its given value, or gone (what others set stays).
  for (const std::string& key : written_) {
    if (any_given_ && given_.getType() == XmlRpc::XmlRpcValue::TypeStruct && given_.hasMember(key))
      pnh_.setParam(key, given_[key]);
    else
      pnh_.deleteParam(key);
  }
}

void WrittenBack::write(const NodeSettings& settings, const mm::Params& params) {
  for (const std::string& key : writeBack(pnh_, settings, params)) written_.insert(key);
}

void keepLiveChanges(NodeSettings* settings,
                     const std::vector<std::pair<std::string, std::string>>& changes) {
  auto& overrides = settings->overrides;
  for (const auto& [key, value] : changes) {
    if (key == realTimeFactorKey().key) continue;
    overrides.erase(std::remove_if(overrides.begin(), overrides.end(),
                                   [&key = key](const auto& o) { return o.first == key; }),
                    overrides.end());
    overrides.emplace_back(key, value);
  }
}

std::unique_ptr<mm::Session> makeSession(const ros::NodeHandle& pnh, const mm::Scene& scene,
                                         const NodeSettings& settings) {
  try {
    return std::make_unique<mm::Session>(scene, settings.session);
  } catch (const mm::MazeFileError& e) {  // the marble where the maze file cannot have it
    throw std::runtime_error(pnh.resolveName("maze") + ": " + e.what());
  } catch (const mm::ParamError& e) {  // the marble where it cannot be: the key is ours
    throw std::runtime_error(pnh.getNamespace() + "/" + e.what());
  }
}

std::string describeRun(const mm::Simulation& sim) {
  const mm::Params& p = sim.params();
  char text[256];
  std::snprintf(text, sizeof text,
                "maze '%s' (%d x %d x %d tiles), model %s, integrator %s, step %g s x %d substeps",
                sim.maze().name().c_str(), sim.maze().size().x(), sim.maze().size().y(),
                sim.maze().size().z(), mm::getParam(p, "model").c_str(),
                mm::getParam(p, "integrator").c_str(), p.step, p.substeps);
  return text;
}

}  // namespace marble_maze_ros
