#include "marble_maze/session.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace marble_maze {

Session::Session(const Scene& scene, const SessionSettings& settings)
    : settings_(settings), sim_(scene) {}

bool Session::passed(double seconds, double since) const {
  // Steps of the current length: `seconds` rounded to a whole number of them (at least one),
  // and the time since rounded likewise (to the step count itself while the step has not
  // changed, whatever the times' rounding), compared without a rounding to an integer that a
  // huge time could overflow.
  const double step = sim_.params().step;
  const double steps = std::max(1.0, std::round(seconds / step));
  return (sim_.time() - since) / step >= steps - 0.5;
}

namespace {

/// The queue's order: by step, and within a step by order (then by arrival).
bool actsBefore(const TiltCommand& a, const TiltCommand& b) {
  return a.step < b.step || (a.step == b.step && a.order < b.order);
}

}  // namespace

bool Session::command(const TiltCommand& command) {
  const auto later = std::upper_bound(queue_.begin(), queue_.end(), command, actsBefore);
  queue_.insert(later, command);
  if (queue_.size() <= kQueueCapacity) return true;
  queue_.pop_back();
  return false;
}

double Session::queuedAhead() const {
  if (queue_.empty() || queue_.back().step <= sim_.steps()) return 0;
  return static_cast<double>(queue_.back().step - sim_.steps()) * sim_.params().step;
}

void Session::retimeQueued(const std::function<std::uint64_t(const TiltCommand&)>& step_of) {
  for (TiltCommand& c : queue_)
    if (c.step > sim_.steps()) c.step = std::max(sim_.steps(), step_of(c));
  std::stable_sort(queue_.begin(), queue_.end(), actsBefore);
}

void Session::apply(const TiltCommand& command) {
  applied_.push_back(command);
  applied_.back().step = sim_.steps();
  if (command.kind == TiltCommand::Kind::Angles)
    sim_.setTargetTilt(command.roll, command.pitch);
  else
    sim_.setTiltRate(command.roll, command.pitch);
  driving_rates_ = command.kind == TiltCommand::Kind::Rates;
  commanded_ = true;
  levelled_ = false;
  last_command_time_ = sim_.time();
}

void Session::run(std::uint64_t count) {
  events_.clear();
  applied_.clear();
  for (std::uint64_t i = 0; i < count; ++i) {
    applyDueCommands();
    applyTimeouts();
    sim_.step();
    events_.insert(events_.end(), sim_.events().begin(), sim_.events().end());
    resetAfterFinish();
  }
}

void Session::applyDueCommands() {
  while (!queue_.empty() && queue_.front().step <= sim_.steps()) {
    apply(queue_.front());
    queue_.pop_front();
  }
}

void Session::applyTimeouts() {
  if (settings_.tilt_timeout > 0 && commanded_ && !levelled_ &&
      passed(settings_.tilt_timeout, last_command_time_)) {
    sim_.setTargetTilt(0, 0);
    levelled_ = true;
    driving_rates_ = false;
  }
  if (settings_.rate_timeout > 0 && driving_rates_ &&
      passed(settings_.rate_timeout, last_command_time_)) {
    sim_.setTiltRate(0, 0);
    driving_rates_ = false;
  }
}

void Session::resetAfterFinish() {
  if (sim_.marble().phase == MarblePhase::Free) return;
  if (!finished_) {
    finished_ = true;
    finished_time_ = sim_.time();
  }
  if (settings_.auto_reset > 0 && passed(settings_.auto_reset, finished_time_)) reset();
}

void Session::reset() {
  sim_.reset();
  queue_.clear();
  finished_ = false;
  levelled_ = false;
  driving_rates_ = false;
  commanded_ = false;
}

void Session::place(const Vec3& position_in_board, const Vec3& velocity, const Vec3& spin) {
  const std::string why = sim_.whyNotPlaceable(position_in_board);
  if (!why.empty()) throw std::invalid_argument("position: " + why);
  if (!velocity.allFinite()) throw std::invalid_argument("velocity: not finite");
  if (!spin.allFinite()) throw std::invalid_argument("angular_velocity: not finite");
  // The rule start_velocity, new physics and a snapshot's restore follow (Params::whyTooFast).
  const Params& p = sim_.params();
  const std::string linear = p.whyTooFast(velocity.stableNorm());
  if (!linear.empty()) throw std::invalid_argument("velocity: " + linear);
  const std::string surface = p.whyTooFast(spin.stableNorm() * p.marble_radius);
  if (!surface.empty())
    throw std::invalid_argument("angular_velocity: its surface's speed " + surface);
  sim_.placeMarble(position_in_board, velocity, spin);
  finished_ = false;
}

void Session::load(const Scene& scene) {
  Simulation next(scene);  // throws on bad physics, leaving this session as it was
  // Time and the step count go on, so that stamps and queued steps keep their order.
  SimulationState state = next.state();
  state.time = sim_.time();
  state.steps = sim_.steps();
  next.restore(state);
  sim_ = next;
  queue_.clear();
  finished_ = levelled_ = driving_rates_ = commanded_ = false;
}

void Session::setParams(const Params& params) {
  sim_.setParams(params);
}

namespace {
// Version 2: each queued command's order, and the time and steps the simulated time counts from.
// Version 3: the timed actions' clocks (the last command's, the finish's) as simulated times
// rather than step counts. A version-1 state (recorded before version 2) is read with order 0 for
// each command, as it was queued then, and its time counted from where it was saved; the clocks
// of versions 1 and 2 count steps of the restoring session's length, as they did.
constexpr std::uint32_t kSnapshotVersion = 3;
}  // namespace

std::vector<std::uint8_t> Session::save() const {
  ByteWriter out;
  out.put(kSnapshotVersion);
  sim_.save(&out);
  out.put(static_cast<std::uint64_t>(queue_.size()));
  for (const TiltCommand& c : queue_) {
    out.put(c.step);
    out.put(static_cast<std::int32_t>(c.kind));
    out.put(c.roll);
    out.put(c.pitch);
    out.put(c.order);
  }
  for (bool flag : {paused_, commanded_, driving_rates_, levelled_, finished_})
    out.put(static_cast<std::uint8_t>(flag));
  out.put(last_command_time_);
  out.put(finished_time_);
  return out.bytes();
}

void Session::restore(const std::vector<std::uint8_t>& bytes) {
  ByteReader in(bytes);
  const auto version = in.get<std::uint32_t>();
  if (version < 1 || version > kSnapshotVersion)
    throw std::runtime_error("snapshot: not a state of this version");
  Simulation sim = sim_;
  sim.restore(&in, version >= 2);
  const auto queued = in.get<std::uint64_t>();
  if (queued > kQueueCapacity)
    throw std::runtime_error("snapshot: more commands than a queue holds");
  std::deque<TiltCommand> queue(queued);
  for (std::size_t k = 0; k < queue.size(); ++k) {
    TiltCommand& c = queue[k];
    const std::string which = "snapshot: queued command " + std::to_string(k) + "'s ";
    c.step = in.get<std::uint64_t>();
    const auto kind = in.get<std::int32_t>();
    if (kind != static_cast<std::int32_t>(TiltCommand::Kind::Angles) &&
        kind != static_cast<std::int32_t>(TiltCommand::Kind::Rates))
      throw std::runtime_error(which + "kind " + std::to_string(kind) +
                               " is neither angles (0) nor rates (1)");
    c.kind = static_cast<TiltCommand::Kind>(kind);
    c.roll = in.get<double>();
    c.pitch = in.get<double>();
    if (!std::isfinite(c.roll) || !std::isfinite(c.pitch))
      throw std::runtime_error(which + "roll or pitch is not finite");
    if (version >= 2) c.order = in.get<std::uint64_t>();
  }
  if (!std::is_sorted(queue.begin(), queue.end(), actsBefore))
    throw std::runtime_error("snapshot: the queued commands are not in the order they act in");
  bool flags[5];
  for (bool& flag : flags) flag = in.get<std::uint8_t>() != 0;
  // The clocks, as times no later than the state's.
  const auto clock = [&](const char* what) {
    if (version >= 3) {
      const double time = in.get<double>();
      if (!std::isfinite(time) || time > sim.time())
        throw std::runtime_error(std::string("snapshot: the ") + what + "'s time " +
                                 exactText(time) + " s is not finite or after the state's");
      return time;
    }
    const auto step = in.get<std::uint64_t>();
    if (step > sim.steps())
      throw std::runtime_error(std::string("snapshot: the ") + what + "'s step " +
                               std::to_string(step) + " is after the state's");
    return sim.time() - static_cast<double>(sim.steps() - step) * sim.params().step;
  };
  const double last_command = clock("last command");
  const double finished = clock("finish");
  if (!in.done()) throw std::runtime_error("snapshot: bytes left over after the state");
  sim_ = sim;
  queue_ = queue;
  paused_ = flags[0];
  commanded_ = flags[1];
  driving_rates_ = flags[2];
  levelled_ = flags[3];
  finished_ = flags[4];
  last_command_time_ = last_command;
  finished_time_ = finished;
  events_.clear();
  applied_.clear();
}

std::uint64_t Session::fingerprint() const {
  return marble_maze::fingerprint(save());
}

}  // namespace marble_maze
