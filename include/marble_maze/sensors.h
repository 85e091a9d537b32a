// What an agent's sensors make of the true state, as a real board's do: a camera that sees the
// marble late, less often than the agent acts and with noise (CyberRunner's), and servos that
// report the board's tilt in steps (Moab's whole degrees). All draws come from the episode's
// random stream, so that a seed gives the same observations bit for bit.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace marble_maze {

struct SensorOptions {
  int delay_periods = 0;      ///< the camera's values reach the agent this many periods late
  int delay_jitter = 0;       ///< plus 0 to this many more, drawn each period (never going back)
  double camera_rate = 0;     ///< Hz: a frame this often, the last held between; 0 every period
  double position_noise = 0;  ///< m: the standard deviation of the noise on a frame's x and y
  double tilt_quantum = 0;    ///< rad: the measured roll and pitch rounded to multiples; 0 exact
};

/// SplitMix64's output for the state before `x` (x plus its increment, mixed): a number from a
/// seed, an environment and an episode alone.
std::uint64_t splitMix64(std::uint64_t x);
/// SplitMix64's next number from `state`, uniform in [0, 1).
double uniformDraw(std::uint64_t* state);

class Sensors {
 public:
  /// A frame of the camera: the marble's x, y and vx, vy, and the next waypoint's dx, dy from it.
  using Frame = std::array<double, 6>;

  /// Throws ParamError naming the option when it is out of range.
  Sensors(const SensorOptions& options, double control_rate);
  /// An episode starts with `truth` as its first frame, seen at once: returns it.
  const Frame& restart(const Frame& truth, std::uint64_t* random);
  /// A control period ended with `truth`: the frame the agent sees now.
  const Frame& see(const Frame& truth, std::uint64_t* random);
  /// The board's tilt as its servos report it.
  double measuredTilt(double tilt) const;

 private:
  /// The camera's frame of `truth`: its position with noise (and the waypoint's offset from that).
  Frame capture(const Frame& truth, std::uint64_t* random) const;

  SensorOptions options_;
  double frames_per_period_ = 1;
  std::vector<Frame> history_;  // the camera's frame at each of the last periods, a ring
  std::uint64_t period_ = 0;    // periods since the episode's start
  std::uint64_t seen_ = 0;      // the period whose frame the agent saw last
};

}  // namespace marble_maze
