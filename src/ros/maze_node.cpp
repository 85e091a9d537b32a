#include "maze_node.h"

#include <tf2_eigen/tf2_eigen.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "marble_maze/in_quotes.h"
#include "wall_throttle.h"

namespace marble_maze_ros {
namespace mm = marble_maze;

namespace {

// Following ROS time, at most this much simulated time (or five timer periods, if longer) is
// caught up in one callback; a longer stall (a suspended process, a jump of the clock) is skipped
// with a warning rather than replayed in a burst.
constexpr double kMaxCatchUp = 1.0;  // s
// With ~clock, each run of steps lasts at most this long, so that commands and services are
// answered in between.
constexpr double kFreeRunSlice = 0.005;  // s of wall time
// What one callback following ROS time or a real-time factor may take on, in substeps (some 0.1
// to 0.3 s of work): a tiny step with many substeps, set live, would otherwise hold the node up
// for minutes catching up a second, its services unanswered.
constexpr double kMostSubstepsPerCall = 1e6;

}  // namespace

MazeNode::MazeNode(ros::NodeHandle nh, ros::NodeHandle pnh) : pnh_(pnh) {
  any_given_ = ros::param::get(pnh.getNamespace(), given_);
  mm::Scene scene;
  settings_ = readSettings(pnh, &scene);
  try {
    session_ = std::make_unique<mm::Session>(scene, settings_.session);
  } catch (const mm::MazeFileError& e) {  // the marble where the maze file cannot have it
    throw std::runtime_error(pnh.resolveName("maze") + ": " + e.what());
  } catch (const mm::ParamError& e) {  // the marble where it cannot be: the key is ours
    throw std::runtime_error(pnh.getNamespace() + "/" + e.what());
  }
  maze_text_ = scene.text;
  maze_source_ = scene.source;
  log_ = std::make_unique<SessionLog>(nh, settings_);
  log_->scene(*session_, maze_text_, maze_source_);

  out_ = std::make_unique<StateOutput>(nh, settings_);
  input_ = std::make_unique<TiltInput>(
      nh,
      [this](const ros::Time& stamp, mm::TiltCommand::Kind kind, double roll, double pitch) {
        return onCommand(stamp, kind, roll, pitch);
      },
      [this]() -> const mm::Params& { return session_->simulation().params(); },
      [this] {
        // In lockstep a refused command is answered too, by the state as it stands (with the
        // stamp of the one before it: nothing moved), so that the agent's loop goes on.
        if (settings_.lockstep > 0 && !session_->paused()) publishDue(true);
      });
  SimControl control;
  control.reset = [this] { return reset(); };
  control.pause = [this] { return pause(); };
  control.resume = [this] { return resume(); };
  control.step = [this](std::uint32_t n, marble_maze::MarbleState* after) {
    return stepPaused(n, after);
  };
  control.place = [this](const mm::Vec3& p, const mm::Vec3& v, const mm::Vec3& w) {
    return place(p, v, w);
  };
  control.load = [this](const std::string& maze) { return load(maze); };
  services_ = std::make_unique<SimServices>(nh, control);
  mm::ParamInfo factor{"real_time_factor",
                       "",
                       "with ~clock: times real time to run at, 0 = as fast as it can",
                       mm::ParamInfo::Type::Number,
                       0,
                       1e6,
                       {},
                       true};
  reconfigure_ = std::make_unique<Reconfigure>(
      pnh, std::vector<mm::ParamInfo>{factor},
      [this](const Reconfigure::Changes& changes) { return reconfigure(changes); },
      [this](const std::string& key) { return valueOf(key); });
  health_ = std::make_unique<Health>(nh, [this] { return healthFigures(); });

  out_->publishScene(session_->simulation(), false);
  writeBackSettings();
  const mm::Params& p = session_->simulation().params();
  const char* mode = settings_.lockstep > 0 ? "lockstep"
                     : settings_.own_clock  ? "own clock"
                                            : "ROS time";
  ROS_INFO(
      "marble_maze: maze '%s' (%d x %d x %d tiles), model %s, integrator %s, step %g s x %d "
      "substeps; time: %s",
      session_->simulation().maze().name().c_str(), session_->simulation().maze().size().x(),
      session_->simulation().maze().size().y(), session_->simulation().maze().size().z(),
      mm::getParam(p, "model").c_str(), mm::getParam(p, "integrator").c_str(), p.step, p.substeps,
      mode);

  warnIfLockstepRounds();
  if (settings_.own_clock || settings_.lockstep > 0) {
    clock_pub_ = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
    reanchor(ros::Time(0));  // ROS time is simulated time
    publishNow();
  }
  if (settings_.own_clock) {
    free_run_start_ = ros::WallTime::now();
    free_run_ = nh.createWallTimer(ros::WallDuration(0.001), &MazeNode::onFreeRun, this);
  } else if (settings_.lockstep <= 0) {
    timer_ = nh.createTimer(ros::Duration(1.0 / settings_.update_rate), &MazeNode::onTimer, this);
    // (On the wall's clock: a timer of ROS time does not fire while a simulated clock has not
    // started.)
    clock_check_ = nh.createWallTimer(
        ros::WallDuration(2.0),
        [](const ros::WallTimerEvent&) {
          if (ros::Time::now().isZero())
            ROS_INFO(
                "marble_maze: waiting for /clock (/use_sim_time is true and no clock has come)");
        },
        true);
  }
  if (settings_.own_clock || settings_.lockstep > 0) {
    // A clock that stands (paused, or in lockstep between commands) goes on being said, 20
    // times a wall second, so that a node started meanwhile knows the time. (Not at zero: ROS
    // takes that for no clock, and a recorder would hold each message until the clock starts.)
    clock_said_ = nh.createWallTimer(ros::WallDuration(0.05), [this](const ros::WallTimerEvent&) {
      if ((settings_.lockstep > 0 || session_->paused()) && !stampNow().isZero()) publishClock();
    });
  }
}

void MazeNode::writeBackSettings() {
  for (const std::string& key : writeBack(pnh_, settings_, session_->simulation().params()))
    written_.insert(key);
}

MazeNode::~MazeNode() {
  // Only the keys it wrote: each back to its given value, or gone (what others set stays).
  for (const std::string& key : written_) {
    if (any_given_ && given_.getType() == XmlRpc::XmlRpcValue::TypeStruct && given_.hasMember(key))
      pnh_.setParam(key, given_[key]);
    else
      pnh_.deleteParam(key);
  }
}

// --- Time ----------------------------------------------------------------------------------------

ros::Time MazeNode::stampNow() const {
  return clock_.stampOfStep(session_->steps());
}

void MazeNode::warnIfLockstepRounds() const {
  const double period = settings_.lockstep, taken = static_cast<double>(stepsPer(period)) * step();
  if (period > 0 && std::abs(taken - period) > 1e-9 * period)
    ROS_WARN(
        "marble_maze: ~lockstep: %g s is not a whole number of steps of %g s; each command "
        "advances %g s",
        period, step(), taken);
}

double MazeNode::mostStepsPerCall() const {
  return std::max(1.0, kMostSubstepsPerCall / session_->simulation().params().substeps);
}

std::uint64_t MazeNode::stepsPer(double seconds) const {
  return std::max<std::uint64_t>(1, std::llround(seconds / step()));
}

void MazeNode::reanchor(const ros::Time& origin) {
  clock_.anchor(origin, session_->steps(), simTime(), stepNs());
  log_->anchor(clock_, session_->steps(), stampNow());
  if (!snapshotted_) {  // the first: a bag started now has where the session stands
    snapshotted_ = true;
    log_->snapshot(*session_, clock_, stampNow());
  }
}

void MazeNode::keepingTime(const std::function<void()>& change) {
  const ros::Time stamp = stampNow();
  change();
  if (!clock_.anchored() || stepNs() == clock_.stepNs()) return;
  reanchor(stamp);
  // A command stamped ahead was queued for its stamp's step of the old length: it goes to the
  // step of the new length its stamp falls on (its order is its stamp).
  session_->retimeQueued([this](const marble_maze::TiltCommand& c) {
    return clock_.stepAt(ros::Time().fromNSec(c.order), session_->steps());
  });
}

void MazeNode::logInput(std::uint8_t kind, const marble_maze::SimInput& input) {
  log_->input(input, kind, session_->steps(), stampNow());
  if (kind != marble_maze::SimInput::PAUSE && kind != marble_maze::SimInput::RESUME)
    log_->snapshot(*session_, clock_, stampNow());
}

void MazeNode::publishClock() {
  if (!clock_pub_) return;
  rosgraph_msgs::Clock msg;
  msg.clock = stampNow();
  clock_pub_.publish(msg);
}

void MazeNode::onTimer(const ros::TimerEvent&) {
  const ros::Time now = ros::Time::now();
  if (now.isZero()) return;  // a simulated clock that has not started (clock_check_ says so)
  if (!clock_.anchored()) {  // the first tick of a running clock
    // Steps on a grid of ROS time (multiples of the step), so that two nodes given the same
    // stamped commands apply them at the same instants: `rosbag play` of a session's commands
    // into a fresh node then follows the session.
    reanchor(onGrid(now, stepNs()));
    last_now_ = now;
    publishNow();
    return;
  }
  if (now < last_now_) {
    ROS_WARN(
        "ROS time went back by %.3f s (a bag looping? a restarted clock?): following it, the "
        "marble back on the start",
        (last_now_ - now).toSec());
    // A bag looping plays its session again from the start: so does the simulation.
    reanchor(onGrid(now, stepNs()));
    out_->clearStamps();
    session_->reset();
    logInput(marble_maze::SimInput::RESET);
    last_now_ = now;
    publishNow();
    return;
  }
  last_now_ = now;
  if (session_->paused()) {
    // The frozen state goes on being published, so that tf does not go stale.
    if (last_frozen_.isZero() || (now - last_frozen_).toSec() >= 1.0 / settings_.publish_rate) {
      last_frozen_ = now;
      publishDue(true);
    }
    return;
  }
  // (Negative after steps taken while paused, which keep their exact stamps: nothing is due, and
  // nothing is published, until ROS time has caught up; /diagnostics says how far ahead.)
  auto due = static_cast<std::int64_t>(clock_.stepsDue(now)) -
             static_cast<std::int64_t>(session_->steps());
  const auto most = static_cast<std::int64_t>(
      std::min(std::max(kMaxCatchUp, 5.0 / settings_.update_rate) / step(), mostStepsPerCall()));
  if (due > most) {
    MARBLE_MAZE_WARN_WALL_THROTTLE(5.0, "simulation fell %.3g s behind ROS time; skipping ahead",
                                   (due - most) * step());
    skipped_steps_ += due - most;
    // The steps taken now end at now's step on the grid.
    reanchor(ros::Time().fromNSec(onGrid(now, stepNs()).toNSec() - most * stepNs()));
    due = most;
  }
  if (due > 0) runSteps(static_cast<std::uint64_t>(due));
}

void MazeNode::onFreeRun(const ros::WallTimerEvent& /*event*/) {
  // ROS time is the simulation's and stands still with it (as a paused Gazebo's does; clock_said_
  // goes on saying it).
  if (session_->paused()) return;
  const ros::WallTime begin = ros::WallTime::now();
  if (settings_.real_time_factor > 0) {
    // As far as the factor allows by now, in slices so that callbacks are answered.
    const double target =
        free_run_start_sim_ + settings_.real_time_factor * (begin - free_run_start_).toSec();
    auto due = static_cast<std::int64_t>(std::floor((target - simTime()) / step() + 1e-9));
    const auto most = static_cast<std::int64_t>(std::min(kMaxCatchUp / step(), mostStepsPerCall()));
    if (due > most) {
      skipped_steps_ += due - most;  // cannot keep up: say so, and aim from here
      free_run_start_ = begin;
      free_run_start_sim_ = simTime();
      due = most;
    }
    if (due > 0) runSteps(static_cast<std::uint64_t>(due));
  } else {
    while ((ros::WallTime::now() - begin).toSec() < kFreeRunSlice) runSteps(100);
  }
  publishClock();
}

void MazeNode::runSteps(std::uint64_t count) {
  const std::uint64_t snapshot_every = stepsPer(1.0);
  for (std::uint64_t i = 0; i < count; ++i) {
    const ros::Time before = stampNow();
    session_->run(1);
    for (const mm::TiltCommand& c : session_->applied()) {
      marble_maze::SimInput input;
      input.roll = c.roll;
      input.pitch = c.pitch;
      log_->input(input,
                  c.kind == mm::TiltCommand::Kind::Angles ? marble_maze::SimInput::TILT
                                                          : marble_maze::SimInput::TILT_RATE,
                  c.step, before);
    }
    for (const mm::Event& e : session_->events()) out_->publishEvent(e, clock_.stampOf(e.time));
    if (session_->steps() % snapshot_every == 0) log_->snapshot(*session_, clock_, stampNow());
    // In lockstep the one state of a control period comes at its end.
    if (settings_.lockstep <= 0) publishDue(false);
  }
}

void MazeNode::publishDue(bool force) {
  // Paused on ROS time, the frozen state is stamped with the ROS time that passes.
  ros::Time stamp = stampNow();
  if (session_->paused() && !settings_.own_clock && settings_.lockstep <= 0)
    stamp = std::max(ros::Time::now(), stamp);
  out_->publishDue(*session_, stamp, stepNs(), force);
}

void MazeNode::publishNow() {
  publishDue(true);
  publishClock();
}

HealthFigures MazeNode::healthFigures() const {
  HealthFigures f;
  f.simulated_time = simTime();
  f.aimed_factor = settings_.own_clock      ? settings_.real_time_factor
                   : settings_.lockstep > 0 ? 0
                                            : 1;
  f.follows_ros_time = !settings_.own_clock && settings_.lockstep <= 0;
  f.ros_time = ros::Time::now().toSec();
  f.skipped_steps = skipped_steps_;
  f.commands = input_->received();
  f.lost = input_->lost();
  f.since_command = input_->last().isZero() ? -1 : (ros::Time::now() - input_->last()).toSec();
  f.queued = session_->queued();
  f.paused = session_->paused();
  if (f.follows_ros_time && clock_.anchored())
    f.ahead = std::max(0.0, (stampNow() - ros::Time::now()).toSec());
  f.lockstep = settings_.lockstep > 0;
  return f;
}

// --- Inputs --------------------------------------------------------------------------------------

double MazeNode::onCommand(const ros::Time& stamp, mm::TiltCommand::Kind kind, double roll,
                           double pitch) {
  const std::uint64_t now = session_->steps();
  if (settings_.lockstep > 0) {
    // A gym-like loop over plain topics: the command acts at once, for one control period.
    // Paused, it waits for the step service's next step, as on any clock (or is replaced by the
    // first command after resume, which acts at the same step).
    session_->command({now, kind, roll, pitch});
    if (!session_->paused()) {  // (paused, no step is taken and no state comes)
      runSteps(stepsPer(settings_.lockstep));
      publishNow();
    }
    return 0;
  }
  // Paused, time stands still: a command acts at the next step taken (by `step`, or on resume),
  // so that an agent stepping the simulation drives it step by step.
  const std::uint64_t at =
      clock_.anchored() && !session_->paused() ? clock_.stepAt(stamp, now) : now;
  // Those that act at one step act in the order of their stamps (a zero stamp: on arrival, at
  // the simulation's time if steps taken while paused put it ahead of ROS time), whatever the
  // order they came in.
  const ros::Time order = stamp.isZero() ? std::max(ros::Time::now(), stampNow()) : stamp;
  if (!session_->command({at, kind, roll, pitch, order.toNSec()}))
    MARBLE_MAZE_WARN_WALL_THROTTLE(
        1.0,
        "tilt commands stamped far ahead fill the queue; dropped the one furthest "
        "ahead");
  return static_cast<double>(at - now) * step();
}

// --- Services ------------------------------------------------------------------------------------

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
  last_frozen_ = ros::Time();
  // Steps taken while paused (`step`) follow on from here in simulated time.
  if (settings_.lockstep <= 0 && !settings_.own_clock && clock_.anchored())
    reanchor(onGrid(std::max(ros::Time::now(), stampNow()), stepNs(), true));
  return "";
}

std::string MazeNode::resume() {
  if (!session_->paused()) return "";
  session_->resume();
  logInput(marble_maze::SimInput::RESUME);
  // The simulation takes up where it stopped: the paused time is not simulated. Steps taken
  // while paused put it ahead of ROS time, which then catches up.
  if (settings_.own_clock) {
    free_run_start_ = ros::WallTime::now();
    free_run_start_sim_ = simTime();
  } else if (settings_.lockstep <= 0 && clock_.anchored()) {
    reanchor(onGrid(std::max(ros::Time::now(), stampNow()), stepNs(), true));
  }
  return "";
}

std::string MazeNode::stepPaused(std::uint32_t steps, marble_maze::MarbleState* after) {
  if (!session_->paused()) return "steps: only while paused (the simulation runs): call pause";
  std::string why = whyTooMuchWork(steps, session_->simulation().params(),
                                   "steps: " + std::to_string(steps) + " steps are");
  if (!why.empty()) return why;
  runSteps(steps);
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
    keepingTime([&] { session_->load(scene); });
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
  writeBackSettings();
  publishNow();
  ROS_INFO("marble_maze: loaded maze '%s'", session_->simulation().maze().name().c_str());
  warnIfLockstepRounds();
  return "";
}

std::string MazeNode::reconfigure(const Reconfigure::Changes& changes) {
  mm::Params params = session_->simulation().params();
  double factor = settings_.real_time_factor;
  try {
    for (const auto& [key, value] : changes) {
      if (key == "real_time_factor") {
        if (!mm::parseFiniteNumber(value, &factor) || factor < 0 || factor > 1e6)
          return "real_time_factor: expected 0..1e6, got " + mm::inQuotes(value);
      } else {
        mm::setParam(params, key, value);
      }
    }
    mm::validate(params);
    std::string why = whyNotRunnable(settings_, params);
    if (!why.empty()) return why;
    keepingTime([&] { session_->setParams(params); });
  } catch (const mm::ParamError& e) {
    return e.what();
  }
  if (factor != settings_.real_time_factor) {
    settings_.real_time_factor = factor;
    free_run_start_ = ros::WallTime::now();
    free_run_start_sim_ = simTime();
  }
  // A value changed live is one of the node's parameters from now on: a maze loaded later takes
  // it over its file's physics, as it takes those the node started with.
  auto& overrides = settings_.overrides;
  for (const auto& [key, value] : changes) {
    if (key == "real_time_factor") continue;
    overrides.erase(std::remove_if(overrides.begin(), overrides.end(),
                                   [&key = key](const auto& o) { return o.first == key; }),
                    overrides.end());
    overrides.emplace_back(key, value);
  }
  writeBackSettings();
  // The latched descriptions say the physics in force: a planner reading `maze` (its tilt limit,
  // its servo) and a recorder reading `scene` start from the new values. (The scene goes before
  // the input's snapshot, as at a load.)
  out_->publishDescription(session_->simulation());
  log_->scene(*session_, maze_text_, maze_source_);
  marble_maze::SimInput input;
  input.params = mm::paramsText(session_->simulation().params());
  logInput(marble_maze::SimInput::PARAMS, input);
  warnIfLockstepRounds();
  return "";
}

std::string MazeNode::valueOf(const std::string& key) const {
  if (key == "real_time_factor") return mm::exactText(settings_.real_time_factor);
  return mm::getParam(session_->simulation().params(), key);
}

}  // namespace marble_maze_ros
