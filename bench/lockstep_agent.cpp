// The ROS lockstep loop as a roscpp agent runs it, for scripts/bench_lockstep.sh: against a node
// started with ~lockstep, it sends ~periods tilt commands (a circling tilt), each after the
// state that answers the one before, and prints the periods a second of wall time and the CPU
// the node spent a period (its process ~node_pid, from /proc). With ~listen_all it also
// subscribes to every topic the node publishes, as a node with every output wanted.
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <topic_tools/shape_shifter.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "marble_maze/BoardTilt.h"
#include "marble_maze/MarbleState.h"

namespace {

/// The CPU seconds process `pid` has spent so far (user and system), from /proc/PID/stat.
double cpuSeconds(int pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
  // Fields after the command's closing parenthesis: state is the 3rd, utime the 14th.
  std::istringstream rest(text.substr(text.rfind(')') + 2));
  std::string field;
  double ticks = 0;
  for (int k = 3; k <= 15 && rest >> field; ++k)
    if (k == 14 || k == 15) ticks += std::stod(field);
  return ticks / static_cast<double>(sysconf(_SC_CLK_TCK));
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "lockstep_agent");
  ros::NodeHandle nh, pnh("~");
  const int periods = pnh.param("periods", 5000);
  const int node_pid = pnh.param("node_pid", 0);
  ros::Time last;
  bool answered = false;
  ros::Subscriber state = nh.subscribe<marble_maze::MarbleState>(
      "marble_state", 10,
      [&](const marble_maze::MarbleState::ConstPtr& s) {
        if (s->header.stamp > last) answered = true, last = s->header.stamp;
      },
      ros::VoidConstPtr(),
      pnh.param("udp", false) ? ros::TransportHints().udp() : ros::TransportHints().tcpNoDelay());
  std::vector<ros::Subscriber> others;
  const boost::function<void(const topic_tools::ShapeShifter::ConstPtr&)> listen =
      [](const topic_tools::ShapeShifter::ConstPtr&) {};
  if (pnh.param("listen_all", false))
    for (const char* topic : {"odom", "/tf", "/clock", "inputs", "snapshot", "events",
                              "marble_marker", "live_markers", "/diagnostics"})
      others.push_back(nh.subscribe(topic, 100, listen));
  ros::Publisher tilt = nh.advertise<marble_maze::BoardTilt>("tilt", 10);
  while (ros::ok() && (tilt.getNumSubscribers() == 0 || state.getNumPublishers() == 0))
    ros::WallDuration(0.01).sleep();
  ros::WallDuration(0.5).sleep();  // (every subscription connected)
  ros::spinOnce();
  const double cpu_before = node_pid ? cpuSeconds(node_pid) : 0;
  const ros::WallTime begin = ros::WallTime::now();
  int done = 0;
  for (; done < periods && ros::ok(); ++done) {
    marble_maze::BoardTilt command;
    command.roll = 0.05 * std::cos(done * 0.01);
    command.pitch = 0.05 * std::sin(done * 0.01);
    answered = false;
    tilt.publish(command);
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(5.0);
    while (!answered && ros::ok() && ros::WallTime::now() < deadline)
      ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.01));
    if (!answered) {
      std::fprintf(stderr, "lockstep_agent: no state after command %d within 5 s\n", done);
      return 1;
    }
  }
  const double wall = (ros::WallTime::now() - begin).toSec();
  const double cpu = node_pid ? cpuSeconds(node_pid) - cpu_before : 0;
  std::printf("%d periods in %.3f s: %.0f periods/s; the node's CPU %.1f us a period\n", done, wall,
              done / wall, 1e6 * cpu / done);
  return 0;
}
