#include "time_policy.h"

#include <algorithm>

#include "clock_owner.h"
#include "follow_ros_time.h"
#include "lockstep.h"
#include "own_clock.h"
#include "wall_throttle.h"

namespace marble_maze_ros {
namespace mm = marble_maze;

namespace {

// What one callback following ROS time or a real-time factor may take on, in substeps (some 0.1
// to 0.3 s of work): a tiny step with many substeps, set live, would otherwise hold the node up
// for minutes catching up a second, its services unanswered.
constexpr double kMostSubstepsPerCall = 1e6;

}  // namespace

double TimePolicy::command(const ros::Time& stamp, mm::TiltCommand::Kind kind, double roll,
                           double pitch) {
  return queueStamped(stamp, kind, roll, pitch);
}

void TimePolicy::keepingTime(const std::function<void()>& change) {
  const ros::Time stamp = stampNow();
  const std::int64_t old_step_ns = c_.clock->stepNs();
  change();
  if (!c_.clock->anchored() || stepNs() == old_step_ns) return;
  c_.reanchor(stamp);
  // A command stamped ahead was queued for its stamp's step of the old length: it goes to the
  // step of the new length its stamp falls on (its order is its stamp).
  c_.session->retimeQueued([this](const mm::TiltCommand& c) {
    return c_.clock->stepAt(ros::Time().fromNSec(c.order), c_.session->steps());
  });
}

void TimePolicy::sayClock() {
  if (!clock_pub_ || clock_pub_.getNumSubscribers() == 0) return;  // (no one to tell)
  rosgraph_msgs::Clock msg;
  msg.clock = stampNow();
  clock_pub_.publish(msg);
}

double TimePolicy::mostStepsPerCall() const {
  return std::max(1.0, kMostSubstepsPerCall / c_.session->simulation().params().substeps);
}

double TimePolicy::queueStamped(const ros::Time& stamp, mm::TiltCommand::Kind kind, double roll,
                                double pitch) {
  mm::Session& session = *c_.session;
  const std::uint64_t now = session.steps();
  // Paused, time stands still: a command acts at the next step taken (by `step`, or on resume),
  // so that an agent stepping the simulation drives it step by step.
  const std::uint64_t at =
      c_.clock->anchored() && !session.paused() ? c_.clock->stepAt(stamp, now) : now;
  // Those that act at one step act in the order of their stamps (a zero stamp: on arrival, at
  // the simulation's time if steps taken while paused put it ahead of ROS time), whatever the
  // order they came in.
  const ros::Time order = stamp.isZero() ? std::max(ros::Time::now(), stampNow()) : stamp;
  if (!session.command({at, kind, roll, pitch, order.toNSec()}))
    MARBLE_MAZE_WARN_WALL_THROTTLE(
        1.0, "tilt commands stamped far ahead fill the queue; dropped the one furthest ahead");
  return static_cast<double>(at - now) * step();
}

void TimePolicy::ownClock(ros::NodeHandle& nh) {
  // (Deep enough that a listener the machine holds up for a moment misses no period of a node
  // that runs free.)
  clock_pub_ = nh.advertise<rosgraph_msgs::Clock>("/clock", 1000);
  refuseSharedClock();
  c_.reanchor(ros::Time(0));
  c_.publish_state(stateStamp(), true);
  sayClock();
  // (Not at zero: ROS takes that for no clock, and a recorder would hold each message until the
  // clock starts.)
  clock_said_ = nh.createWallTimer(ros::WallDuration(0.05), [this](const ros::WallTimerEvent&) {
    if (clockStands() && !stampNow().isZero()) sayClock();
  });
}

std::unique_ptr<TimePolicy> makeTimePolicy(const PolicyContext& context) {
  if (context.settings->lockstep > 0) return std::make_unique<Lockstep>(context);
  if (context.settings->own_clock) return std::make_unique<OwnClock>(context);
  return std::make_unique<FollowRosTime>(context);
}

}  // namespace marble_maze_ros
