#include "marble_maze/session.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace marble_maze {

Session::Session(const Scene& scene, const SessionSettings& settings)
    : settings_(settings), sim_(scene) {}

std::uint64_t Session::stepsOf(double seconds) const {
  return std::max<std::uint64_t>(1, std::llround(seconds / sim_.params().step));
}

bool Session::command(const TiltCommand& command) {
  const auto later = std::upper_bound(
      queue_.begin(), queue_.end(), command.step,
      [](std::uint64_t step, const TiltCommand& queued) { return step < queued.step; });
  queue_.insert(later, command);
  if (queue_.size() <= kQueueCapacity) return true;
  queue_.pop_back();
  return false;
}

void Session::apply(const TiltCommand& command) {
  if (command.kind == TiltCommand::Kind::Angles)
    sim_.setTargetTilt(command.roll, command.pitch);
  else
    sim_.setTiltRate(command.roll, command.pitch);
  driving_rates_ = command.kind == TiltCommand::Kind::Rates;
  commanded_ = true;
  levelled_ = false;
  last_command_step_ = sim_.steps();
}

void Session::run(std::uint64_t count) {
  events_.clear();
  for (std::uint64_t i = 0; i < count; ++i) {
    while (!queue_.empty() && queue_.front().step <= sim_.steps()) {
      apply(queue_.front());
      queue_.pop_front();
    }
    // The timed actions, at the step their time comes.
    if (settings_.tilt_timeout > 0 && commanded_ && !levelled_ &&
        stepsSinceCommand() >= stepsOf(settings_.tilt_timeout)) {
      sim_.setTargetTilt(0, 0);
      levelled_ = true;
      driving_rates_ = false;
    }
    if (settings_.rate_timeout > 0 && driving_rates_ &&
        stepsSinceCommand() >= stepsOf(settings_.rate_timeout)) {
      sim_.setTiltRate(0, 0);
      driving_rates_ = false;
    }
    sim_.step();
    events_.insert(events_.end(), sim_.events().begin(), sim_.events().end());
    if (sim_.marble().phase == MarblePhase::Free) continue;
    if (!finished_) {
      finished_ = true;
      finished_step_ = sim_.steps();
    }
    if (settings_.auto_reset > 0 && sim_.steps() - finished_step_ >= stepsOf(settings_.auto_reset))
      reset();
  }
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
  if (!why.empty()) throw std::invalid_argument(why);
  if (!velocity.allFinite() || !spin.allFinite())
    throw std::invalid_argument("the velocity and the spin must be finite");
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

}  // namespace marble_maze
