#include "recording.h"

#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "marble_maze/maze_file.h"

namespace marble_maze_ros {
namespace mm = marble_maze;

Recording readRecording(const std::string& path) {
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagUnindexedException& e) {
    throw std::runtime_error(path + ": " + e.what() +
                             " (a recording that did not end: `rosbag reindex " + path +
                             "` writes its index from what it holds)");
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
  Recording r;
  std::vector<marble_maze::SceneDescription> scenes;
  std::vector<ros::Time> scene_received;
  std::vector<marble_maze::SimSnapshot> snapshots;  // in the order received
  std::vector<ros::Time> snapshot_received;
  for (const rosbag::MessageInstance& m : rosbag::View(bag)) {
    if (auto scene = m.instantiate<marble_maze::SceneDescription>()) {
      scenes.push_back(*scene);
      scene_received.push_back(m.getTime());
    } else if (auto snapshot = m.instantiate<marble_maze::SimSnapshot>()) {
      snapshots.push_back(*snapshot);
      snapshot_received.push_back(m.getTime());
    } else if (auto input = m.instantiate<marble_maze::SimInput>()) {
      r.inputs.push_back(*input);
    } else if (auto state = m.instantiate<marble_maze::MarbleState>()) {
      r.states.push_back(*state);
    }
  }
  std::stable_sort(r.inputs.begin(), r.inputs.end(),
                   [](const auto& a, const auto& b) { return a.index < b.index; });
  for (std::size_t k = 1; k < r.inputs.size(); ++k) {
    if (r.inputs[k].index == r.inputs[k - 1].index)
      throw std::runtime_error(path + ": input " + std::to_string(r.inputs[k].index) +
                               " is in it twice: two sessions (two nodes, or one restarted)? " +
                               "rosbag filter can keep one's topics");
    if (r.inputs[k].index != r.inputs[k - 1].index + 1)
      throw std::runtime_error(path + ": inputs " + std::to_string(r.inputs[k - 1].index + 1) +
                               " to " + std::to_string(r.inputs[k].index - 1) + " are missing");
    // The node starts over where ROS time goes back: the runs' states share stamps, and the
    // recorder's times loop with them, so that neither tells one run's messages from another's.
    if (r.inputs[k].header.stamp < r.inputs[k - 1].header.stamp)
      throw std::runtime_error(
          path + ": ROS time went back while it was recorded (input " +
          std::to_string(r.inputs[k].index) + " is stamped " +
          std::to_string(r.inputs[k].header.stamp.toSec()) + " s, input " +
          std::to_string(r.inputs[k - 1].index) + " " +
          std::to_string(r.inputs[k - 1].header.stamp.toSec()) +
          " s: a looping rosbag play, a clock set back); its runs cannot be told apart, so "
          "record each in a bag of its own");
  }
  // Each scene is the maze of the snapshots received after it, and of those received at the same
  // instant: the node publishes a scene before the snapshot of its instant, but a recorder may
  // receive two messages of one instant (a lockstep node's latched scene and first snapshot, at
  // one simulated time) in either order.
  std::vector<std::size_t> scene_after;  // the snapshots received before each scene
  scene_after.reserve(scene_received.size());
  for (const ros::Time& t : scene_received)
    scene_after.push_back(static_cast<std::size_t>(
        std::lower_bound(snapshot_received.begin(), snapshot_received.end(), t) -
        snapshot_received.begin()));
  // A recorder that started late missed the inputs made before it subscribed: the replay starts
  // from the first snapshot that holds them all and has a scene recorded before it.
  const std::uint64_t first_input = r.inputs.empty() ? 0 : r.inputs.front().index;
  const std::size_t first_scene_before = scenes.empty() ? snapshots.size() : scene_after.front();
  std::size_t chosen = snapshots.size();
  for (std::size_t k = first_scene_before; k < snapshots.size() && chosen == snapshots.size(); ++k)
    if (snapshots[k].inputs >= first_input) chosen = k;
  if (chosen == snapshots.size()) {
    if (scenes.empty() || snapshots.empty() || first_scene_before >= snapshots.size())
      throw std::runtime_error(path + ": no marble_maze/SceneDescription (scene) followed by " +
                               "a marble_maze/SimSnapshot (snapshot)");
    throw std::runtime_error(path +
                             ": no marble_maze/SimSnapshot (snapshot) that the recorded "
                             "inputs follow on from");
  }
  std::size_t scene = scenes.size();
  for (std::size_t k = 0; k < scenes.size(); ++k)
    if (scene_after[k] <= chosen) scene = k;
  // Inputs were made after the snapshot (later snapshots count them) but none was recorded: the
  // replay would play the session without its tilts.
  std::uint64_t counted = 0;
  for (const auto& snapshot : snapshots) counted = std::max(counted, snapshot.inputs);
  if (r.inputs.empty() && counted > snapshots[chosen].inputs)
    throw std::runtime_error(path + ": no marble_maze/SimInput (inputs), though its snapshots " +
                             "count " + std::to_string(counted - snapshots[chosen].inputs) +
                             " made: a replay needs the session's inputs recorded");
  r.scene = scenes[scene];
  r.snapshot = snapshots[chosen];
  const std::uint64_t held = r.snapshot.inputs;
  r.inputs.erase(std::remove_if(r.inputs.begin(), r.inputs.end(),
                                [held](const marble_maze::SimInput& i) { return i.index < held; }),
                 r.inputs.end());
  std::stable_sort(r.states.begin(), r.states.end(),
                   [](const auto& a, const auto& b) { return a.header.stamp < b.header.stamp; });
  return r;
}

mm::Params Replayer::paramsOf(const mm::Params& recorded) const {
  mm::Params params = recorded;
  for (const auto& [key, value] : overrides_) mm::setParam(params, key, value);
  mm::validate(params);
  return params;
}

Replayer::Replayer(const Recording& recording, const Overrides& overrides)
    : recording_(recording), overrides_(overrides) {
  mm::Scene scene = mm::parseScene(recording.scene.maze_text, recording.scene.maze_source);
  const mm::Params recorded = mm::paramsFromText(recording.snapshot.params);
  mm::replaceParams(&scene, paramsOf(recorded));
  mm::SessionSettings settings;
  settings.tilt_timeout = recording.scene.tilt_timeout;
  settings.rate_timeout = recording.scene.rate_timeout;
  settings.auto_reset = recording.scene.auto_reset;
  session_ = std::make_unique<mm::Session>(scene, settings);
  session_->restore(recording.snapshot.state);
  // The commands the snapshot still held come again among the recorded inputs, each at the step
  // it acted at (the node logs a command as it acts): they act from there, at their simulated
  // time under any step. From the queue, which counts steps, they would act at another time
  // under another step length (one queued two steps ahead acted 1 ms early at half the step: the
  // board 2 mrad ahead, a millisecond of its rate limit).
  session_->dropQueued();
  const mm::SimSnapshot& snapshot = recording.snapshot;
  const auto recorded_ns = std::llround(recorded.step * 1e9);
  clock_.anchor(snapshot.anchor_stamp, snapshot.anchor_step, snapshot.anchor_time, recorded_ns);
  followStep();  // under another step (--set step=...), on from the snapshot's stamp
  scheduleInputs(recorded.step);
}

void Replayer::scheduleInputs(double snapshot_step) {
  // Each input acts at the simulated time it acted at in the session: at its own step while the
  // replay's step is the session's, and at the first step at or after that time under another
  // (--set step=...). The time runs on in stretches of one step length, each begun at a load or
  // a reconfigure, in the session and in the replay alike.
  const auto& inputs = recording_.inputs;
  due_.resize(inputs.size());
  std::uint64_t recorded_from = session_->steps(), replayed_from = session_->steps();
  double recorded_step = snapshot_step;
  double replayed_step = session_->simulation().params().step;
  double recorded_at = 0, replayed_at = 0;  // s of simulated time since the snapshot
  std::uint64_t earliest = replayed_from;   // inputs stay in their order
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const mm::SimInput& in = inputs[i];
    const std::uint64_t since = in.step > recorded_from ? in.step - recorded_from : 0;
    const double at = recorded_at + static_cast<double>(since) * recorded_step;
    std::uint64_t due = replayed_from + since;  // the same step length: the same step
    if (replayed_step != recorded_step || replayed_from != recorded_from) {
      const double steps = std::ceil((at - replayed_at) / replayed_step - 1e-9);
      due = replayed_from + static_cast<std::uint64_t>(std::max(0.0, steps));
    }
    due_[i] = earliest = std::max(earliest, due);
    if (in.kind == mm::SimInput::LOAD || in.kind == mm::SimInput::PARAMS) {
      replayed_at += static_cast<double>(due_[i] - replayed_from) * replayed_step;
      recorded_at = at;
      recorded_from = in.step;
      replayed_from = due_[i];
      const mm::Params recorded = mm::paramsFromText(in.params);
      recorded_step = recorded.step;
      replayed_step = paramsOf(recorded).step;
    }
  }
}

std::vector<const marble_maze::SimInput*> Replayer::applyDue() {
  std::vector<const marble_maze::SimInput*> applied;
  const auto& inputs = recording_.inputs;
  while (next_ < inputs.size() && due_[next_] <= session_->steps()) {
    const marble_maze::SimInput& in = inputs[next_++];
    using K = marble_maze::SimInput;
    switch (in.kind) {
      case K::TILT:
      case K::TILT_RATE:
        // As applied in the session, in the order it applied them (those the snapshot still
        // held among them: see the constructor).
        session_->command(
            {session_->steps(),
             in.kind == K::TILT ? mm::TiltCommand::Kind::Angles : mm::TiltCommand::Kind::Rates,
             in.roll, in.pitch, std::numeric_limits<std::uint64_t>::max()});
        break;
      case K::RESET:
        session_->reset();
        break;
      case K::PAUSE:
        session_->pause();
        break;
      case K::RESUME:
        session_->resume();
        break;
      case K::PLACE:
        session_->place({in.position.x, in.position.y, in.position.z},
                        {in.velocity.x, in.velocity.y, in.velocity.z},
                        {in.angular_velocity.x, in.angular_velocity.y, in.angular_velocity.z});
        break;
      case K::LOAD:
      case K::PARAMS:
        // (The session took them: only parameters set over the recording's can be refused, a
        // marble too wide for the loaded maze's start, say.)
        try {
          if (in.kind == K::LOAD) {
            mm::Scene scene = mm::parseScene(in.maze_text, in.maze_source);
            mm::replaceParams(&scene, paramsOf(mm::paramsFromText(in.params)));
            session_->load(scene);
          } else {
            session_->setParams(paramsOf(mm::paramsFromText(in.params)));
          }
        } catch (const std::runtime_error& e) {
          if (overrides_.empty()) throw;  // (what the bag holds: said as it is)
          throw mm::ParamError(
              std::string(in.kind == K::LOAD ? "the maze load" : "the reconfigure") +
              " recorded as input " + std::to_string(in.index) + " (at " +
              std::to_string(in.header.stamp.toSec()) + " s) refuses them: " + e.what());
        }
        followStep();
        break;
      case K::ANCHOR:
        clock_.anchor(in.anchor_stamp, session_->steps(), in.anchor_time, stepNs());
        break;
      default:
        throw std::runtime_error("inputs: unknown kind " + std::to_string(in.kind));
    }
    applied.push_back(&in);
  }
  return applied;
}

void Replayer::followStep() {
  // As the node does: a new step length ties the steps to ROS time anew where they stand (the
  // node's ANCHOR input at this step came before the change, with the old length).
  if (clock_.stepNs() != stepNs())
    clock_.anchor(stamp(), session_->steps(), session_->simulation().time(), stepNs());
}

ros::Time Replayer::end() const {
  ros::Time end;
  if (!recording_.states.empty()) end = recording_.states.back().header.stamp;
  if (!recording_.inputs.empty()) end = std::max(end, recording_.inputs.back().header.stamp);
  return end;
}

}  // namespace marble_maze_ros
