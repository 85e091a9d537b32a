// A recorded session, as a bag holds it (record.launch), and its re-simulation: the session
// restored from the bag's first snapshot, every later input applied at the step it took effect
// at (under another step length, at the first step at or after its simulated time), and the
// clock anchored where the original's was, so that each step carries the original's stamp. Shared
// by the node's replay (~bag) and `resimulate`; reads bags with rosbag's C++ API, with no ROS
// master.
#pragma once

#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "marble_maze/MarbleState.h"
#include "marble_maze/SceneDescription.h"
#include "marble_maze/SimInput.h"
#include "marble_maze/SimSnapshot.h"
#include "marble_maze/session.h"
#include "sim_clock.h"

namespace marble_maze_ros {

struct Recording {
  /// The last received before the snapshot, or at its instant.
  marble_maze::SceneDescription scene;
  /// The first that a scene was received before (or with) and the recorded inputs follow on from.
  marble_maze::SimSnapshot snapshot;
  std::vector<marble_maze::SimInput> inputs;     ///< those after the snapshot, in order
  std::vector<marble_maze::MarbleState> states;  ///< marble_state as recorded, in stamp order
};

/// Reads a bag; throws std::runtime_error saying what it lacks (a scene, a snapshot).
Recording readRecording(const std::string& path);

/// Keys to set over the recorded physics ("--set" of the runner): a re-run under other physics.
using Overrides = std::vector<std::pair<std::string, std::string>>;

class Replayer {
 public:
  /// The scene and the snapshot's state; throws (ParamError, MazeFileError, std::runtime_error)
  /// when the recording cannot be simulated.
  explicit Replayer(const Recording& recording, const Overrides& overrides = {});

  /// Applies the inputs due before the next step; returns those applied, in order.
  std::vector<const marble_maze::SimInput*> applyDue();
  /// Takes the next step (after applyDue).
  void step() { session_->run(1); }

  marble_maze::Session& session() { return *session_; }
  const SimClock& clock() const { return clock_; }
  ros::Time stamp() const { return clock_.stampOfStep(session_->steps()); }
  std::int64_t stepNs() const { return std::llround(session_->simulation().params().step * 1e9); }
  /// The stamp of the last recorded state, or of the last input if later.
  ros::Time end() const;

 private:
  /// The recorded parameters with the overrides set over them, checked.
  marble_maze::Params paramsOf(const marble_maze::Params& recorded) const;
  /// After a load, a reconfigure or a step set over the recorded one: the clock goes on at the
  /// step length now in force, from where the steps stand.
  void followStep();
  /// Works out the step of the replay at which each input acts (due_), from the snapshot's
  /// recorded step length on.
  void scheduleInputs(double snapshot_step);

  const Recording& recording_;
  Overrides overrides_;
  std::unique_ptr<marble_maze::Session> session_;
  SimClock clock_;
  std::vector<std::uint64_t> due_;  // the step of the replay each input acts before
  std::size_t next_ = 0;            // the next input to apply
};

}  // namespace marble_maze_ros
