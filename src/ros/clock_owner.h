// A node that owns /clock must be its only publisher: two clocks on one master interleave, and
// every node on /use_sim_time sees time go back and forth with no word from either.
#pragma once

#include <string>
#include <vector>

namespace marble_maze_ros {

/// The nodes the master lists as publishing `topic`, but `self`.
std::vector<std::string> otherPublishers(const std::string& topic, const std::string& self);

/// Throws std::runtime_error naming the other publishers of /clock, when there are any (call it
/// once /clock is advertised, so that of two nodes started together, one sees the other).
void refuseSharedClock();

}  // namespace marble_maze_ros
