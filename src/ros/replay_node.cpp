// replay: plays a recorded session (record.launch) live again, from the bag's first snapshot,
// with the recorded inputs applied at their steps: it publishes tf, markers, marble_state and
// events as the original did, stamped as the original was, and /clock (so run the rest of the
// graph, RViz too, on /use_sim_time). The states are the original's bit for bit at any rate.
// It reads the bag itself rather than taking its topics from `rosbag play`, whose transport
// gives no order between /clock and the inputs. Parameters: ~bag (the file), ~rate (times real
// time, 1), ~wait (true: start when marble_state has a subscriber, so that a recorder of the
// replay misses nothing; false), ~keep_alive (false: exit when the recording ends, as `rosbag
// play` does; true: stay, its last state shown); ~world_frame, ~board_frame, ~marble_frame as
// the node's.
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>

#include <memory>

#include "clock_owner.h"
#include "node_settings.h"
#include "recording.h"
#include "run_node.h"
#include "state_output.h"

namespace {
namespace mm = marble_maze;
using marble_maze_ros::NodeSettings;

class ReplayNode {
 public:
  ReplayNode(ros::NodeHandle nh, const ros::NodeHandle& pnh) : nh_(nh) {
    std::string bag;
    if (!pnh.getParam("bag", bag))
      throw std::runtime_error(pnh.resolveName("bag") + ": required: a bag of record.launch");
    rate_ = marble_maze_ros::readNumber(pnh, "rate", 1.0, 1e-6, 1e6);
    wait_ = marble_maze_ros::readFlag(pnh, "wait", false);
    keep_alive_ = marble_maze_ros::readFlag(pnh, "keep_alive", false);
    recording_ = marble_maze_ros::readRecording(bag);
    replay_ = std::make_unique<marble_maze_ros::Replayer>(recording_);
    NodeSettings settings;
    settings.publish_rate = recording_.scene.publish_rate;
    settings.marker_rate = recording_.scene.marker_rate;
    settings.frames = marble_maze_ros::readFrames(pnh);
    out_ = std::make_unique<marble_maze_ros::StateOutput>(nh, settings);
    clock_pub_ = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
    marble_maze_ros::refuseSharedClock();
    out_->publishScene(replay_->session().simulation(), false);
    // (The recording's span is of ROS time: a session paused meanwhile simulated less.)
    ROS_INFO(
        "replay: %s from simulated %.3f s, %.3f s of the recording's time, at %g times real "
        "time",
        bag.c_str(), replay_->session().simulation().time(),
        (replay_->end() - replay_->stamp()).toSec(), rate_);
    start_wall_ = ros::WallTime::now();
    start_sim_ = replay_->session().simulation().time();
    timer_ = nh.createWallTimer(ros::WallDuration(0.001), &ReplayNode::onTimer, this);
  }

 private:
  void onTimer(const ros::WallTimerEvent&) {
    if (wait_) {
      if (!out_->stateSubscribed()) return;
      wait_ = false;
      start_wall_ = ros::WallTime::now();
    }
    const mm::Session& session = replay_->session();
    if (!started_) {  // the state the snapshot holds, if the original published one then
      out_->publishDue(session, replay_->stamp(), replay_->stepNs(), false);
      started_ = true;
    }
    const double target = start_sim_ + rate_ * (ros::WallTime::now() - start_wall_).toSec();
    while (session.simulation().time() < target) {
      bool shown = false;  // a reset, a place or a load is shown at once, as the original did
      for (const marble_maze::SimInput* in : replay_->applyDue()) {
        if (in->kind == marble_maze::SimInput::LOAD) out_->publishScene(session.simulation(), true);
        shown = shown || in->kind == marble_maze::SimInput::RESET ||
                in->kind == marble_maze::SimInput::PLACE || in->kind == marble_maze::SimInput::LOAD;
      }
      if (shown) out_->publishDue(session, replay_->stamp(), replay_->stepNs(), true);
      if (replay_->stamp() >= replay_->end()) {
        ROS_INFO("replay: the recording ends at %.3f s%s", replay_->stamp().toSec(),
                 keep_alive_ ? "" : "; exiting");
        timer_.stop();
        // (roscpp sends what is published from a queue of its own: a moment for the last
        // messages to reach their subscribers before the node goes.)
        if (!keep_alive_)
          exit_timer_ = nh_.createWallTimer(
              ros::WallDuration(kLinger),
              [](const ros::WallTimerEvent&) { ros::requestShutdown(); }, true);
        break;
      }
      replay_->step();
      for (const mm::Event& e : session.events())
        out_->publishEvent(e, replay_->clock().stampOf(e.time));
      out_->publishDue(session, replay_->stamp(), replay_->stepNs(), false);
    }
    rosgraph_msgs::Clock clock;
    clock.clock = replay_->stamp();
    clock_pub_.publish(clock);
  }

  static constexpr double kLinger = 1.0;  // s of wall time

  ros::NodeHandle nh_;
  double rate_ = 1;
  bool wait_ = false;
  bool keep_alive_ = false;
  bool started_ = false;
  marble_maze_ros::Recording recording_;
  std::unique_ptr<marble_maze_ros::Replayer> replay_;
  std::unique_ptr<marble_maze_ros::StateOutput> out_;
  ros::Publisher clock_pub_;
  ros::WallTimer timer_, exit_timer_;
  ros::WallTime start_wall_;
  double start_sim_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  return marble_maze_ros::runNode<ReplayNode>(argc, argv, "replay");
}
