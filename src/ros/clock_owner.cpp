#include "clock_owner.h"

#include <ros/master.h>
#include <ros/this_node.h>

#include <stdexcept>

namespace marble_maze_ros {

std::vector<std::string> otherPublishers(const std::string& topic, const std::string& self) {
  // getSystemState answers [publishers, subscribers, services], each [[name, [nodes]], ...].
  XmlRpc::XmlRpcValue request, response, payload;
  request[0] = self;
  std::vector<std::string> others;
  if (!ros::master::execute("getSystemState", request, response, payload, false)) return others;
  XmlRpc::XmlRpcValue& publishers = payload[0];
  // XmlRpcValue's begin() walks a struct's members, not an array's items: index it.
  for (int i = 0; i < publishers.size(); ++i) {  // NOLINT(modernize-loop-convert)
    if (static_cast<std::string>(publishers[i][0]) != topic) continue;
    for (int j = 0; j < publishers[i][1].size(); ++j) {
      const std::string node = publishers[i][1][j];
      if (node != self) others.push_back(node);
    }
  }
  return others;
}

void refuseSharedClock() {
  const std::vector<std::string> others = otherPublishers("/clock", ros::this_node::getName());
  if (others.empty()) return;
  std::string names;
  for (const std::string& node : others) names += (names.empty() ? "" : ", ") + node;
  throw std::runtime_error(
      "/clock: " + names + " publishes it already; this node would own it (~clock, ~lockstep " +
      "or a replay), and two clocks on one master make time jump back and forth: stop the " +
      "other, or run this one on a master of its own");
}

}  // namespace marble_maze_ros
