// A simulation as programs drive it, without ROS: tilt commands that take effect at a given
// step, the timed actions of a game (the board levels when commands stop, rate commands run out,
// the marble goes back to the start after a hole or the goal), pause, steps on demand, placing
// the marble, another maze, other physics. Everything happens at a step and is timed in
// simulated time, never when a timer fires, so the same calls give bit-identical states: the
// node (with a clock policy around it), simulate and replay share it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <string>
#include <vector>

#include "marble_maze/simulation.h"

namespace marble_maze {

/// The timed actions, in seconds of simulated time; 0 switches one off.
struct SessionSettings {
  double tilt_timeout = 0;  ///< without a command this long, the board levels
  double rate_timeout = 1;  ///< without a command this long, tilt rates stop (targets hold)
  double auto_reset = 0;    ///< this long after a hole or the goal, the marble is put back
};

/// A tilt command: target angles (rad) or tilt rates (rad/s), applied at the start of a step.
struct TiltCommand {
  enum class Kind { Angles, Rates };
  std::uint64_t step = 0;  ///< applied just before this step is taken (the next one if past)
  Kind kind = Kind::Angles;
  double roll = 0;
  double pitch = 0;
  /// Orders the commands of one step (a node's: their stamps, in ns): they act in its order,
  /// and those of equal order in their order of arrival.
  std::uint64_t order = 0;
};

/// The way to drive a simulation: a Simulation with the command queue, the timed actions, pause,
/// place, load and snapshots that the node, the runner (simulate) and the replay share, so that
/// the same inputs mean the same in each.
class Session {
 public:
  /// Throws ParamError when the scene's parameters are inconsistent, and MazeFileError when the
  /// marble cannot start where the scene's file puts it.
  explicit Session(const Scene& scene, const SessionSettings& settings = SessionSettings());

  /// Queues a command in the order of its step and then of its `order` (equal ones keep their
  /// order of arrival). False when the queue was full: the command for the latest step was
  /// dropped.
  bool command(const TiltCommand& command);
  /// Takes `count` steps, paused or not: due commands first, then the timed actions. The events
  /// of these steps are in events().
  void run(std::uint64_t count);

  /// The marble back on the start at rest, the board at its initial tilt, commands dropped.
  void reset();
  /// Puts the marble at a board-frame position with a world-frame velocity and spin; throws
  /// std::invalid_argument naming the problem (inside a tile, off the board), changing nothing.
  void place(const Vec3& position_in_board, const Vec3& velocity, const Vec3& spin);
  /// Another maze and its physics; throws (ParamError, or MazeFileError for a start its file
  /// gives where the marble cannot be) changing nothing when they are bad.
  void load(const Scene& scene);
  /// Other physics from the next step; throws ParamError changing nothing when inconsistent.
  void setParams(const Params& params);

  void pause() { paused_ = true; }
  void resume() { paused_ = false; }
  bool paused() const { return paused_; }

  const Simulation& simulation() const { return sim_; }
  const SessionSettings& settings() const { return settings_; }
  std::uint64_t steps() const { return sim_.steps(); }
  /// The events of the last run(), in order.
  const std::vector<Event>& events() const { return events_; }
  std::size_t queued() const { return queue_.size(); }
  /// s of simulated time, at the step in force, until the last queued command acts (0 when none
  /// waits).
  double queuedAhead() const;
  /// Drops the queued commands, the rest of the state kept (a replay's: the recorded inputs hold
  /// each command again as it acted).
  void dropQueued() { queue_.clear(); }
  /// Moves each queued command not yet due (for a step after the current one) to the step
  /// `step_of` gives it (none before the current one), in the queue's order: a node's commands
  /// stamped ahead, after a change of the step's length, to their stamps' steps of the new one.
  void retimeQueued(const std::function<std::uint64_t(const TiltCommand&)>& step_of);
  /// s of simulated time since the step the last command was applied at (since the start if
  /// none was).
  double timeSinceCommand() const { return sim_.time() - last_command_time_; }
  /// The commands applied in the last run(), in order, each with the step it took effect at.
  const std::vector<TiltCommand>& applied() const { return applied_; }

  /// Every value the next step depends on but the scene (maze and physics): the simulation's
  /// state, the queued commands, the pause and the timed actions' clocks, bit for bit.
  std::vector<std::uint8_t> save() const;
  /// Back to a saved state (of a session with the same maze; under other physics the board moves
  /// under this session's servo and limits). Throws std::runtime_error ("snapshot: ...", naming
  /// the value) on bytes that are not a state or hold a value no session saves (not finite, out
  /// of range, commands out of order), changing nothing.
  void restore(const std::vector<std::uint8_t>& bytes);
  /// A fingerprint of save(): equal states have equal fingerprints.
  std::uint64_t fingerprint() const;

  static constexpr std::size_t kQueueCapacity = 10000;

 private:
  // A step's stages around the simulation's: the commands due, the timed actions, the step,
  // then the auto reset of a finished marble once its time has come.
  void applyDueCommands();
  void apply(const TiltCommand& command);
  /// The tilt and rate timeouts, at the step their time comes.
  void applyTimeouts();
  void resetAfterFinish();
  /// Whether `seconds` have passed since the simulated time `since`, both counted in whole steps
  /// of the current length: at the very step the steps count to while the step stays the same,
  /// and within a step of that time across a change of the step.
  bool passed(double seconds, double since) const;

  SessionSettings settings_;
  Simulation sim_;
  std::deque<TiltCommand> queue_;
  std::vector<Event> events_;
  std::vector<TiltCommand> applied_;
  bool paused_ = false;
  bool commanded_ = false;  // a command was applied since the start or the last reset
  // The timed actions' clocks, in s of simulated time rather than steps, so that they keep their
  // time across a change of step.
  double last_command_time_ = 0;
  bool driving_rates_ = false;
  bool levelled_ = false;
  bool finished_ = false;
  double finished_time_ = 0;
};

}  // namespace marble_maze
