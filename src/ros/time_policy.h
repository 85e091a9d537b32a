// How ROS time and the simulation's steps relate: one of three policies, chosen once at start
// from the node's settings (makeTimePolicy):
//  - FollowRosTime (the default): the steps due are the ROS time elapsed (wall time, or /clock
//    under /use_sim_time), looked at ~update_rate times a second;
//  - OwnClock (~clock): the node owns /clock and runs as fast as it can (~real_time_factor 0)
//    or at a multiple of real time;
//  - Lockstep (~lockstep): each tilt command advances one control period, then the state is
//    published.
// A policy decides what advances the simulation and when, where a command acts, and the stamp
// a state is published with; the node keeps the session, its inputs and its outputs. Each
// policy's timers call a method the unit tests call directly, with no ROS master.
#pragma once

#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "health.h"
#include "marble_maze/session.h"
#include "node_settings.h"
#include "sim_clock.h"

namespace marble_maze_ros {

/// What a policy drives: the node's session, its clock and what the node does for it.
struct PolicyContext {
  marble_maze::Session* session = nullptr;
  SimClock* clock = nullptr;
  const NodeSettings* settings = nullptr;
  /// Takes `count` steps (logging their inputs, events and snapshots), publishing each step's
  /// state that is due when `publish_each`.
  std::function<void(std::uint64_t count, bool publish_each)> run_steps;
  /// Publishes the state as it stands, stamped `stamp`; `force` even when none is due.
  std::function<void(const ros::Time& stamp, bool force)> publish_state;
  /// Ties the current step to ROS time `origin` (and says so on `inputs`).
  std::function<void(const ros::Time& origin)> reanchor;
  /// ROS time went back to `now`: the session starts over, tied to it.
  std::function<void(const ros::Time& now)> restart;
};

class TimePolicy {
 public:
  explicit TimePolicy(const PolicyContext& context) : c_(context) {}
  virtual ~TimePolicy() = default;
  TimePolicy(const TimePolicy&) = delete;
  TimePolicy& operator=(const TimePolicy&) = delete;

  /// How it relates time, for the node's first log line.
  virtual const char* name() const = 0;
  /// Ties the simulation to time and starts the timers that advance it.
  virtual void start(ros::NodeHandle& nh) = 0;
  /// A tilt command that came with `stamp`: queued for the step it acts at (in lockstep, run
  /// for a period); returns how long it is held, in s.
  virtual double command(const ros::Time& stamp, marble_maze::TiltCommand::Kind kind, double roll,
                         double pitch);
  /// A command refused (not finite).
  virtual void refused() {}
  virtual void paused() {}
  virtual void resumed() {}
  /// The node's own keys that dynamic_reconfigure offers beside the core's under this policy.
  virtual std::vector<marble_maze::ParamInfo> liveKeys() const { return {}; }
  /// The real-time factor in the settings changed live.
  virtual void realTimeFactorChanged() {}
  /// Whether a state is published after each step that makes one due (not in lockstep: after
  /// each period).
  virtual bool publishesEachStep() const { return true; }
  /// Whether a state shown at once after a change between steps may repeat the last stamp (in
  /// lockstep time moves only with commands).
  virtual bool repeatsStamps() const { return false; }
  /// The stamp the state as it stands is published with.
  virtual ros::Time stateStamp() const { return stampNow(); }
  /// Runs `change` (another maze, other physics); a step of another length from then on is
  /// re-anchored where the session stood, so that its steps keep to ROS time's rate, and the
  /// commands stamped ahead go to their stamps' steps of that length.
  void keepingTime(const std::function<void()>& change);
  /// Says /clock at the simulation's time, when it owns the clock.
  void sayClock();
  /// The time figures of /diagnostics: the factor aimed at, whether ROS time is followed, how far
  /// ahead of it, steps skipped.
  virtual void fillHealth(HealthFigures* figures) const = 0;

 protected:
  ros::Time stampNow() const { return c_.clock->stampOfStep(c_.session->steps()); }
  double step() const { return c_.session->simulation().params().step; }
  std::int64_t stepNs() const { return std::llround(step() * 1e9); }
  /// How many steps one callback may take on, at the substeps in force: more are skipped.
  double mostStepsPerCall() const;
  /// Queues a command at the step its stamp falls on (paused: the next step taken); returns how
  /// long it is held.
  double queueStamped(const ros::Time& stamp, marble_maze::TiltCommand::Kind kind, double roll,
                      double pitch);
  /// Advertises /clock, ties step 0 to ROS time 0 (ROS time is simulated time) and says it;
  /// while clockStands(), it goes on being said 20 times a wall second, so that a node started
  /// meanwhile knows the time.
  void ownClock(ros::NodeHandle& nh);
  virtual bool clockStands() const { return false; }

  PolicyContext c_;
  std::uint64_t skipped_steps_ = 0;  // steps skipped to catch up since the start

 private:
  ros::Publisher clock_pub_;
  ros::WallTimer clock_said_;
};

/// The policy the settings choose.
std::unique_ptr<TimePolicy> makeTimePolicy(const PolicyContext& context);

}  // namespace marble_maze_ros
