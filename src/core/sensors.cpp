#include "marble_maze/sensors.h"

#include <cmath>

#include "marble_maze/params.h"

namespace marble_maze {

std::uint64_t splitMix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

double uniformDraw(std::uint64_t* state) {
  const std::uint64_t x = splitMix64(*state);
  *state += 0x9e3779b97f4a7c15ull;
  return static_cast<double>(x >> 11) * 0x1p-53;
}

namespace {

/// A standard normal number (Box-Muller), written out rather than std::normal_distribution,
/// whose numbers differ from one standard library to another.
double normalDraw(std::uint64_t* state) {
  const double u = 1.0 - uniformDraw(state);  // (0, 1]
  const double v = uniformDraw(state);
  return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * M_PI * v);
}

}  // namespace

Sensors::Sensors(const SensorOptions& options, double control_rate) : options_(options) {
  const auto refuse = [](const char* name, double value, const char* range) {
    throw ParamError(std::string(name) + ": " + exactText(value) + " is out of range " + range);
  };
  if (options.delay_periods < 0 || options.delay_periods > 1000)
    refuse("delay_periods", options.delay_periods, "[0, 1000]");
  if (options.delay_jitter < 0 || options.delay_jitter > 1000)
    refuse("delay_jitter", options.delay_jitter, "[0, 1000]");
  if (!(options.camera_rate >= 0 && std::isfinite(options.camera_rate)))
    refuse("camera_rate", options.camera_rate, "[0, inf) Hz");
  if (!(options.position_noise >= 0 && options.position_noise <= 1))
    refuse("position_noise", options.position_noise, "[0, 1] m");
  if (!(options.tilt_quantum >= 0 && options.tilt_quantum <= 0.5))
    refuse("tilt_quantum", options.tilt_quantum, "[0, 0.5] rad");
  if (options.camera_rate > 0 && options.camera_rate < control_rate)
    frames_per_period_ = options.camera_rate / control_rate;
  history_.resize(static_cast<std::size_t>(options.delay_periods) +
                  static_cast<std::size_t>(options.delay_jitter) + 1);
}

Sensors::Frame Sensors::capture(const Frame& truth, std::uint64_t* random) const {
  Frame frame = truth;
  if (options_.position_noise > 0) {
    const double nx = options_.position_noise * normalDraw(random);
    const double ny = options_.position_noise * normalDraw(random);
    frame[0] += nx, frame[1] += ny;
    frame[4] -= nx, frame[5] -= ny;  // the waypoint is where it is; the marble seems elsewhere
  }
  return frame;
}

const Sensors::Frame& Sensors::restart(const Frame& truth, std::uint64_t* random) {
  period_ = seen_ = 0;
  history_[0] = capture(truth, random);
  return history_[0];
}

const Sensors::Frame& Sensors::see(const Frame& truth, std::uint64_t* random) {
  const std::size_t size = history_.size();
  const Frame& last = history_[period_ % size];
  ++period_;
  // A frame when the camera's clock passes a whole frame within this period.
  const bool frame_due = std::floor(static_cast<double>(period_) * frames_per_period_) >
                         std::floor(static_cast<double>(period_ - 1) * frames_per_period_);
  history_[period_ % size] = frame_due ? capture(truth, random) : last;
  std::uint64_t delay = static_cast<std::uint64_t>(options_.delay_periods);
  if (options_.delay_jitter > 0)
    delay += std::min<std::uint64_t>(
        static_cast<std::uint64_t>(uniformDraw(random) * (options_.delay_jitter + 1)),
        static_cast<std::uint64_t>(options_.delay_jitter));
  const std::uint64_t wanted = period_ > delay ? period_ - delay : 0;
  seen_ = std::max(seen_, wanted);
  return history_[seen_ % size];
}

double Sensors::measuredTilt(double tilt) const {
  if (options_.tilt_quantum <= 0) return tilt;
  return std::round(tilt / options_.tilt_quantum) * options_.tilt_quantum;
}

}  // namespace marble_maze
