// record: a session's topics into a bag, losing none of a burst. `rosbag record` subscribes with
// a queue of 100 messages that no option changes, and a lockstep agent's burst of commands or a
// paused node's queued commands let loose make more inputs than that at once: the bag then lacks
// inputs and cannot be replayed. This writes what rosbag record writes (each message as it came,
// its connection header, the time it came in ROS time), through subscriptions as deep as asked,
// and when stopped it writes what had come before closing the bag (roscpp would drop it).
//
//   ~bag     the bag file to write (required)
//   ~topics  the topics, a list or one text of names separated by spaces (required)
//   ~queue   each subscription's queue, in messages (default 100000)
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <topic_tools/shape_shifter.h>

#include <algorithm>
#include <atomic>
#include <boost/make_shared.hpp>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "node_settings.h"

namespace marble_maze_ros {
namespace {

std::vector<std::string> topicsFrom(const ros::NodeHandle& pnh) {
  XmlRpc::XmlRpcValue value;
  const std::string name = pnh.resolveName("topics");
  if (!pnh.getParam("topics", value)) throw std::runtime_error(name + ": required");
  std::vector<std::string> topics;
  if (value.getType() == XmlRpc::XmlRpcValue::TypeArray) {
    for (int k = 0; k < value.size(); ++k) {
      if (value[k].getType() != XmlRpc::XmlRpcValue::TypeString)
        throw std::runtime_error(name + ": expected topic names, item " + std::to_string(k) +
                                 " is not a text");
      topics.push_back(static_cast<std::string>(value[k]));
    }
  } else if (value.getType() == XmlRpc::XmlRpcValue::TypeString) {
    std::istringstream words(static_cast<std::string>(value));
    for (std::string topic; words >> topic;) topics.push_back(topic);
  } else {
    throw std::runtime_error(name + ": expected a list of topic names or a text of them");
  }
  if (topics.empty()) throw std::runtime_error(name + ": no topic");
  return topics;
}

class Recorder {
 public:
  Recorder(ros::NodeHandle nh, const ros::NodeHandle& pnh) {
    const std::string path = readText(pnh, "bag", "");
    if (path.empty()) throw std::runtime_error(pnh.resolveName("bag") + ": required");
    const double queue = readNumber(pnh, "queue", 100000, 1, 1e7);
    const std::vector<std::string> topics = topicsFrom(pnh);
    // (A bad name is refused before the bag is opened; a name given twice, as `chat /chat`, is
    // recorded once.)
    std::vector<std::string> resolved;
    for (const std::string& topic : topics) {
      std::string full;
      try {
        full = nh.resolveName(topic);
      } catch (const ros::InvalidNameException& e) {
        throw std::runtime_error(pnh.resolveName("topics") + ": " + e.what());
      }
      if (std::find(resolved.begin(), resolved.end(), full) != resolved.end()) {
        ROS_WARN("%s: %s is given twice; recorded once", pnh.resolveName("topics").c_str(),
                 full.c_str());
        continue;
      }
      resolved.push_back(full);
    }
    most_early_ = static_cast<std::size_t>(queue);
    for (const std::string& topic : resolved) {
      // Any type: the first publisher's connection says which (as rosbag record subscribes).
      // Written under its full name, as `rosbag record -a` writes it (rosbag play --topics /tilt).
      ros::SubscribeOptions options;
      options.topic = topic;
      options.queue_size = static_cast<std::uint32_t>(queue);
      options.md5sum = ros::message_traits::md5sum<topic_tools::ShapeShifter>();
      options.datatype = ros::message_traits::datatype<topic_tools::ShapeShifter>();
      options.helper = boost::make_shared<ros::SubscriptionCallbackHelperT<const Event&>>(
          [this, topic](const Event& event) { write(topic, event); });
      options.transport_hints = ros::TransportHints().tcpNoDelay();
      subscribers_.push_back(nh.subscribe(options));
    }
    // (Opened last: nothing is written before the loop runs the callbacks, and a constructor
    // that threw after it would leave a closed, indexed PATH.active behind.)
    open(pnh.resolveName("bag"), path);
    // (A relative path is taken from the node's working directory: roslaunch's is ROS_HOME.)
    std::error_code error;
    const std::filesystem::path full_path = std::filesystem::absolute(path, error);
    const std::string shown = error ? path : full_path.string();
    ROS_INFO("record: %zu topics into %s (%s.active until it stops)", resolved.size(),
             shown.c_str(), shown.c_str());
  }

  ~Recorder() {
    // (A bag that cannot be written is said, not thrown out of a destructor.)
    try {
      finish();
    } catch (const std::exception& e) {
      ROS_ERROR("record: %s: %s", activePath().c_str(), e.what());
    }
  }

 private:
  using Event = ros::MessageEvent<topic_tools::ShapeShifter const>;

  void finish() {
    subscribers_.clear();
    // A clock that never started: what came is kept, at the earliest time a bag holds.
    for (const Early& e : early_) writeAt(e.topic, ros::TIME_MIN, e.event);
    tellDropped();
    bag_.close();
    std::error_code error;
    std::filesystem::rename(activePath(), path_, error);
    if (error)
      ROS_ERROR("record: could not name %s %s: %s", activePath().c_str(), path_.c_str(),
                error.message().c_str());
  }

  /// Opens PATH.active, which is named PATH when it is closed, as rosbag record does: a recorder
  /// killed outright leaves a file that says it did not end, not one that looks whole and cannot
  /// be read. Its chunks are small, so that such a file loses little: `rosbag reindex` gives back
  /// all it holds up to its last whole chunk. A PATH.active already there is such a recording,
  /// and is left alone; a PATH already there is replaced now, as an open for writing replaces a
  /// file, rather than when this one closes (after a kill it would pass for this recording).
  void open(const std::string& name, const std::string& path) {
    path_ = path;
    const std::string active = activePath();
    std::error_code error;
    if (std::filesystem::exists(active, error))
      throw std::runtime_error(name + ": " + active +
                               " is there: a recording that did not end (`rosbag reindex` it, "
                               "or remove it)");
    if (std::filesystem::exists(path, error)) {
      ROS_INFO("record: replaces %s", path.c_str());
      std::filesystem::remove(path, error);
    }
    try {
      bag_.setChunkThreshold(kChunkBytes);
      bag_.open(active, rosbag::bagmode::Write);
    } catch (const rosbag::BagException& e) {
      throw std::runtime_error(name + ": " + active + ": " + e.what());
    }
  }

  /// The name the bag is written under until it is closed.
  std::string activePath() const { return path_ + ".active"; }

  void write(const std::string& topic, const Event& event) {
    // The time it came in ROS time, as rosbag record stamps it: a simulated clock's in sim time.
    // Before that clock starts (a node's latched scene, a lockstep node's first messages) a
    // message waits for its first tick: written at time zero, it would stretch the bag over the
    // decades to a clock played from another bag.
    const ros::Time now = ros::Time::now();
    if (now.isZero()) {
      if (early_.size() < most_early_) {
        early_.push_back({topic, event});
      } else if (dropped_++ == 0) {
        ROS_WARN(
            "record: more than %zu messages (~queue) before the clock started: dropping "
            "the later ones, from %s",
            most_early_, topic.c_str());
      }
      return;
    }
    for (const Early& e : early_) writeAt(e.topic, now, e.event);
    early_.clear();
    tellDropped();
    writeAt(topic, now, event);
  }

  void tellDropped() {
    if (dropped_ == 0) return;
    ROS_ERROR(
        "record: dropped %llu messages that came before the clock started: the bag lacks "
        "them (a larger ~queue keeps them)",
        static_cast<unsigned long long>(dropped_));
    dropped_ = 0;
  }

  void writeAt(const std::string& topic, const ros::Time& time, const Event& event) {
    bag_.write(topic, time, *event.getMessage(), event.getConnectionHeaderPtr());
  }

  struct Early {
    std::string topic;
    Event event;
  };
  // Some two seconds of a session's messages: what a recorder killed outright loses at most.
  static constexpr std::uint32_t kChunkBytes = 64 * 1024;
  std::string path_;  // the bag's name once it is closed
  rosbag::Bag bag_;   // written as path_.active, closed (its index written) when the node ends
  std::vector<ros::Subscriber> subscribers_;
  std::vector<Early> early_;  // come before ROS time was valid, in their order
  std::size_t most_early_ = 0;
  std::uint64_t dropped_ = 0;  // of the early ones, beyond most_early_
};

std::atomic<bool> g_stop{false};

}  // namespace
}  // namespace marble_maze_ros

// Stopped (Ctrl-C, roslaunch's SIGINT, SIGTERM), the recorder first writes the messages that had
// come in: roscpp's own handler would shut down at once and drop its queue, the end of a burst.
int main(int argc, char** argv) {
  using marble_maze_ros::g_stop;
  ros::init(argc, argv, "record", ros::init_options::NoSigintHandler);
  // (A second signal ends it at once, as it would any program.)
  for (const int signal : {SIGINT, SIGTERM})
    std::signal(signal, [](int received) {
      g_stop = true;
      std::signal(received, SIG_DFL);
    });
  ros::NodeHandle nh, pnh("~");  // (they outlive a throwing constructor: see run_node.h)
  try {
    marble_maze_ros::Recorder recorder(nh, pnh);
    ros::CallbackQueue& queue = *ros::getGlobalCallbackQueue();
    while (!g_stop && ros::ok()) queue.callAvailable(ros::WallDuration(0.1));
    queue.callAvailable();  // what had come when the stop came
  } catch (const std::exception& e) {
    ROS_FATAL("%s", e.what());
    return 1;
  }
  ros::shutdown();
  return 0;
}
