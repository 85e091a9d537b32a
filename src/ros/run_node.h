// The main() of every node of the package: a node class built from its handles and spun, and a
// refusal at start (a bad parameter, a bag that cannot be read) a FATAL and exit status 1.
#pragma once

#include <ros/ros.h>

#include <csignal>
#include <exception>
#include <string>

namespace marble_maze_ros {

template <typename Node>
int runNode(int argc, char** argv, const char* name) {
  ros::init(argc, argv, name);
  // SIGTERM (kill, docker stop) ends a node as Ctrl-C does, through its destructors: roscpp
  // handles only SIGINT.
  std::signal(SIGTERM, [](int) { ros::requestShutdown(); });
  // The handles outlive a throwing constructor: with the last handle gone roscpp shuts down and
  // the FATAL message naming the bad parameter would never be printed.
  ros::NodeHandle nh, pnh("~");
  try {
    Node node(nh, pnh);
    ros::spin();
  } catch (const std::exception& e) {
    // A refused parameter ("/node/key: why") stays on the parameter server when the node ends:
    // given by `rosrun ... _key:=`, it would refuse the next start too, so the way to clear it
    // is said.
    const std::string what = e.what(), name = what.substr(0, what.find(": "));
    bool on_server = false;
    try {
      on_server = name.rfind(pnh.getNamespace() + "/", 0) == 0 && ros::param::has(name);
    } catch (const ros::Exception&) {  // not a name at all (a message of another form)
    }
    if (on_server)
      ROS_FATAL(
          "%s\n(the parameter server keeps this value after the node ends: mend it where it "
          "was given, a launch file or `_KEY:=`, or clear it with `rosparam delete %s`)",
          what.c_str(), name.c_str());
    else
      ROS_FATAL("%s", what.c_str());
    return 1;
  }
  return 0;
}

}  // namespace marble_maze_ros
