// record: a session's topics into a bag, losing none of a burst. `rosbag record` subscribes with
// a queue of 100 messages that no option changes, and a lockstep agent's burst of commands or a
// paused node's queued commands let loose make more inputs than that at once: the bag then lacks
// inputs and cannot be replayed. This writes what rosbag record writes (each message as it came,
// its connection header, the time it came in ROS time), through subscriptions as deep as asked.
//
//   ~bag     the bag file to write (required)
//   ~topics  the topics, a list or one text of names separated by spaces (required)
//   ~queue   each subscription's queue, in messages (default 100000)
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <topic_tools/shape_shifter.h>

#include <boost/make_shared.hpp>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "node_settings.h"
#include "run_node.h"

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
  Recorder(ros::NodeHandle nh, ros::NodeHandle pnh) {
    const std::string path = readText(pnh, "bag", "");
    if (path.empty()) throw std::runtime_error(pnh.resolveName("bag") + ": required");
    const double queue = readNumber(pnh, "queue", 100000, 1, 1e7);
    const std::vector<std::string> topics = topicsFrom(pnh);
    std::vector<std::string> resolved;  // (a bad name refused before the bag is opened)
    for (const std::string& topic : topics) {
      try {
        resolved.push_back(nh.resolveName(topic));
      } catch (const ros::InvalidNameException& e) {
        throw std::runtime_error(pnh.resolveName("topics") + ": " + e.what());
      }
    }
    try {
      bag_.open(path, rosbag::bagmode::Write);
    } catch (const rosbag::BagException& e) {
      throw std::runtime_error(pnh.resolveName("bag") + ": " + path + ": " + e.what());
    }
    most_early_ = static_cast<std::size_t>(queue);
    for (std::size_t k = 0; k < topics.size(); ++k) {
      const std::string& topic = topics[k];
      // Any type: the first publisher's connection says which (as rosbag record subscribes).
      ros::SubscribeOptions options;
      options.topic = resolved[k];
      options.queue_size = static_cast<std::uint32_t>(queue);
      options.md5sum = ros::message_traits::md5sum<topic_tools::ShapeShifter>();
      options.datatype = ros::message_traits::datatype<topic_tools::ShapeShifter>();
      // (Written under the name as given, as rosbag record writes it: a relative one plays back
      // into the player's namespace, and `rosbag play --topics tilt` finds it.)
      options.helper = boost::make_shared<ros::SubscriptionCallbackHelperT<const Event&>>(
          [this, topic](const Event& event) { write(topic, event); });
      options.transport_hints = ros::TransportHints().tcpNoDelay();
      subscribers_.push_back(nh.subscribe(options));
    }
    ROS_INFO("record: %zu topics into %s", topics.size(), path.c_str());
  }

  ~Recorder() {
    subscribers_.clear();
    // A clock that never started: what came is kept, at the earliest time a bag holds.
    for (const Early& e : early_) writeAt(e.topic, ros::TIME_MIN, e.event);
  }

 private:
  using Event = ros::MessageEvent<topic_tools::ShapeShifter const>;

  void write(const std::string& topic, const Event& event) {
    // The time it came in ROS time, as rosbag record stamps it: a simulated clock's in sim time.
    // Before that clock starts (a node's latched scene, a lockstep node's first messages) a
    // message waits for its first tick: written at time zero, it would stretch the bag over the
    // decades to a clock played from another bag.
    const ros::Time now = ros::Time::now();
    if (now.isZero()) {
      if (early_.size() < most_early_) early_.push_back({topic, event});
      return;
    }
    for (const Early& e : early_) writeAt(e.topic, now, e.event);
    early_.clear();
    writeAt(topic, now, event);
  }

  void writeAt(const std::string& topic, const ros::Time& time, const Event& event) {
    bag_.write(topic, time, *event.getMessage(), event.getConnectionHeaderPtr());
  }

  struct Early {
    std::string topic;
    Event event;
  };
  rosbag::Bag bag_;  // closed (its index written) when the node ends
  std::vector<ros::Subscriber> subscribers_;
  std::vector<Early> early_;  // come before ROS time was valid, in their order
  std::size_t most_early_ = 0;
};

}  // namespace
}  // namespace marble_maze_ros

int main(int argc, char** argv) {
  return marble_maze_ros::runNode<marble_maze_ros::Recorder>(argc, argv, "record");
}
