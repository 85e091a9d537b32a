#include "lockstep.h"

#include <algorithm>
#include <cmath>

namespace marble_maze_ros {
namespace mm = marble_maze;

void Lockstep::start(ros::NodeHandle& nh) {
  ownClock(nh);
}

std::uint64_t Lockstep::stepsPerPeriod() const {
  return std::max<std::uint64_t>(1, std::llround(c_.settings->lockstep / step()));
}

double Lockstep::command(const ros::Time& /*stamp*/, mm::TiltCommand::Kind kind, double roll,
                         double pitch) {
  // The command acts at once, for one control period (the period, not its stamp, is the time
  // it takes). Paused, it waits for the step service's next step, as on any clock (or is
  // replaced by the first command after resume, which acts at the same step).
  c_.session->command({c_.session->steps(), kind, roll, pitch});
  if (!c_.session->paused()) {  // (paused, no step is taken and no state comes)
    c_.run_steps(stepsPerPeriod(), false);
    c_.publish_state(stateStamp(), true);
    sayClock();
  }
  return 0;
}

void Lockstep::refused() {
  // Answered too, by the state as it stands (with the stamp of the one before it: nothing
  // moved), so that the agent's loop goes on.
  if (!c_.session->paused()) c_.publish_state(stateStamp(), true);
}

void Lockstep::fillHealth(HealthFigures* f) const {
  f->aimed_factor = 0;
  f->running = "running in lockstep: each tilt command advances one period";
  f->aimed_means = "lockstep: none, the commands'";
}

}  // namespace marble_maze_ros
