#include "maze_node.h"

#include <tf2_eigen/tf2_eigen.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>  // std::invalid_argument, a placement refused

namespace marble_maze_ros {
namespace mm = marble_maze;

MazeNode::MazeNode(ros::NodeHandle nh, const ros::NodeHandle& pnh) : written_(pnh) {
  mm::Scene scene;
  settings_ = readSettings(pnh, &scene);
  session_ = makeSession(pnh, scene, settings_);
  maze_text_ = scene.text;
  maze_source_ = scene.source;
  log_ = std::make_unique<SessionLog>(nh, settings_);
  log_->scene(*session_, maze_text_, maze_source_);
  out_ = std::make_unique<StateOutput>(nh, settings_);

  PolicyContext context;
  context.session = session_.get();
  context.clock = &clock_;
  context.settings = &settings_;
  context.run_steps = [this](std::uint64_t count, bool each) { runSteps(count, each); };
  context.publish_state = [this](const ros::Time& stamp, bool force) {
    publishState(stamp, force);
  };
  context.reanchor = [this](const ros::Time& origin) { reanchor(origin); };
  context.restart = [this](const ros::Time& now) { restart(now); };
  time_ = makeTimePolicy(context);

  input_ = std::make_unique<TiltInput>(
      nh,
      [this](const ros::Time& stamp, mm::TiltCommand::Kind kind, double roll, double pitch) {
        return time_->command(stamp, kind, roll, pitch);
      },
      [this]() -> const mm::Params& { return session_->simulation().params(); },
      [this] { time_->refused(); });
  SimControl control;
  control.reset = [this] { return reset(); };
  control.pause = [this] { return pause(); };
  control.resume = [this] { return resume(); };
  control.step = [this](std::uint32_t n, marble_maze::MarbleState* s) { return stepPaused(n, s); };
  control.place = [this](const mm::Vec3& p, const mm::Vec3& v, const mm::Vec3& w) {
    return place(p, v, w);
  };
  control.load = [this](const std::string& maze) { return load(maze); };
  services_ = std::make_unique<SimServices>(control);
  services_->advertise(nh);
  reconfigure_ = std::make_unique<Reconfigure>(
      time_->liveKeys(), [this](const Reconfigure::Changes& c) { return reconfigure(c); },
      [this](const std::string& key) { return valueOf(key); });
  reconfigure_->advertise(pnh);
  health_ = std::make_unique<Health>(nh, [this] { return healthFigures(); });

  out_->publishScene(session_->simulation(), false);
  written_.write(settings_, session_->simulation().params());
  ROS_INFO("marble_maze: %s; time: %s", describeRun(session_->simulation()).c_str(), time_->name());
  time_->start(nh);
}

// --- What the time policy drives --------------------------------------------------------------

std::int64_t MazeNode::stepNs() const {
  return std::llround(session_->simulation().params().step * 1e9);
}

void MazeNode::runSteps(std::uint64_t count, bool publish_each) {
  const std::uint64_t snapshot_every =
      std::max<std::uint64_t>(1, std::llround(1.0 / session_->simulation().params().step));
  for (std::uint64_t i = 0; i < count; ++i) {
    const ros::Time before = stampNow();
    session_->run(1);
    log_->applied(*session_, before);
    for (const mm::Event& e : session_->events()) out_->publishEvent(e, clock_.stampOf(e.time));
    if (session_->steps() % snapshot_every == 0) log_->snapshot(*session_, clock_, stampNow());
    if (publish_each) publishState(time_->stateStamp(), false);
  }
}

void MazeNode::publishState(const ros::Time& stamp, bool force) {
  out_->publishDue(*session_, stamp, stepNs(), force, time_->repeatsStamps());
}

void MazeNode::publishNow() {
  publishState(time_->stateStamp(), true);
  time_->sayClock();
}

void MazeNode::reanchor(const ros::Time& origin) {
  clock_.anchor(origin, session_->steps(), session_->simulation().time(), stepNs());
  log_->anchor(clock_, session_->steps(), stampNow());
  if (!snapshotted_) {  // the first: a bag started now has where the session stands
    snapshotted_ = true;
    log_->snapshot(*session_, clock_, stampNow());
  }
}

void MazeNode::restart(const ros::Time& now) {
  reanchor(now);
  out_->clearStamps();
  session_->reset();
  logInput(marble_maze::SimInput::RESET);
}

void MazeNode::logInput(std::uint8_t kind, const marble_maze::SimInput& input) {
  log_->input(input, kind, session_->steps(), stampNow());
  if (kind != marble_maze::SimInput::PAUSE && kind != marble_maze::SimInput::RESUME)
    log_->snapshot(*session_, clock_, stampNow());
}

HealthFigures MazeNode::healthFigures() const {
  HealthFigures f;
  f.simulated_time = session_->simulation().time();
  f.ros_time = ros::Time::now().toSec();
  input_->fillHealth(&f);
  f.queued = session_->queued(), f.queued_ahead = session_->queuedAhead();
  f.paused = session_->paused();
  time_->fillHealth(&f);
  return f;
}

// --- Services ----------------------------------------------------------------------------------

std::string MazeNode::reset() {
  session_->reset();
  logInput(marble_maze::SimInput::RESET);
  publishNow();
  return "";
}

std::string MazeNode::pause() {
  if (session_->paused()) return "";
  session_->pause();
  logInput(marble_maze::SimInput::PAUSE);
  time_->paused();
  return "";
}

std::string MazeNode::resume() {
  if (!session_->paused()) return "";
  session_->resume();
  logInput(marble_maze::SimInput::RESUME);
  time_->resumed();
  return "";
}

std::string MazeNode::stepPaused(std::uint32_t steps, marble_maze::MarbleState* after) {
  if (!session_->paused()) return "steps: only while paused (the simulation runs): call pause";
  std::string why = mm::whyTooMuchWork(steps, session_->simulation().params(),
                                       "steps: " + std::to_string(steps) + " steps are");
  if (!why.empty()) return why;
  runSteps(steps, time_->publishesEachStep());
  publishNow();
  *after = out_->stateOf(session_->simulation(), stampNow());
  return "";
}

std::string MazeNode::place(const mm::Vec3& position, const mm::Vec3& velocity,
                            const mm::Vec3& spin) {
  try {
    session_->place(position, velocity, spin);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  marble_maze::SimInput input;
  input.position = tf2::toMsg(position);
  tf2::toMsg(velocity, input.velocity);
  tf2::toMsg(spin, input.angular_velocity);
  logInput(marble_maze::SimInput::PLACE, input);
  publishNow();
  return "";
}

std::string MazeNode::load(const std::string& maze) {
  mm::Scene scene;
  try {
    scene = sceneFor(maze, settings_);
    const std::string why = whyNotRunnable(settings_, scene.params);
    if (!why.empty()) return "maze: " + maze + ": " + why;
    time_->keepingTime([&] { session_->load(scene); });
  } catch (const mm::MazeFileError& e) {
    return std::string("maze: ") + e.what();
  } catch (const mm::ParamError& e) {
    return e.what();
  }
  settings_.maze = maze;
  maze_text_ = scene.text;
  maze_source_ = scene.source;
  log_->scene(*session_, maze_text_, maze_source_);
  marble_maze::SimInput input;
  input.maze_text = maze_text_;
  input.maze_source = maze_source_;
  input.params = mm::paramsText(session_->simulation().params());
  logInput(marble_maze::SimInput::LOAD, input);
  out_->publishScene(session_->simulation(), true);
  reconfigure_->publishUpdate();
  changed();
  publishNow();
  ROS_INFO("marble_maze: loaded maze '%s'", session_->simulation().maze().name().c_str());
  return "";
}

std::string MazeNode::reconfigure(const Reconfigure::Changes& changes) {
  mm::Params params = session_->simulation().params();
  double factor = settings_.real_time_factor;
  try {
    for (const auto& [key, value] : changes) {
      if (key == realTimeFactorKey().key)
        factor = parseRealTimeFactor(value);
      else
        mm::setParam(params, key, value);
    }
    fitToLockstep(settings_, &params);
    mm::validate(params);
    std::string why = whyNotRunnable(settings_, params);
    if (!why.empty()) return why;
    time_->keepingTime([&] { session_->setParams(params); });
  } catch (const mm::ParamError& e) {
    return e.what();
  }
  if (factor != settings_.real_time_factor) {
    settings_.real_time_factor = factor;
    time_->realTimeFactorChanged();
  }
  keepLiveChanges(&settings_, changes);  // one of the node's parameters from now on
  // The latched descriptions say the physics in force: a planner reading `maze` (its tilt limit,
  // its servo) and a recorder reading `scene` start from the new values. (The scene goes before
  // the input's snapshot, as at a load.)
  out_->publishDescription(session_->simulation());
  log_->scene(*session_, maze_text_, maze_source_);
  marble_maze::SimInput input;
  input.params = mm::paramsText(session_->simulation().params());
  logInput(marble_maze::SimInput::PARAMS, input);
  changed();
  return "";
}

std::string MazeNode::valueOf(const std::string& key) const {
  if (key == realTimeFactorKey().key) return mm::exactText(settings_.real_time_factor);
  return mm::getParam(session_->simulation().params(), key);
}

void MazeNode::changed() {
  written_.write(settings_, session_->simulation().params());
}

}  // namespace marble_maze_ros
