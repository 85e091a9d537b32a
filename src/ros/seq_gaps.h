// Messages lost on the way, from the gaps in their publishers' header.seq (roscpp and rospy
// number each publisher's messages on a topic 1, 2, 3...). No ROS in it: the node's TiltInput
// feeds it.
//
// One source (a topic and a publisher's name) may carry several series: `rosbag play` sends the
// messages of every publisher it recorded under its own name, each with its recorded seq, so two
// recorded agents arrive interleaved, and a looped bag or a restarted publisher starts again from
// a lower seq. So a message that continues no series starts one; one that starts above another
// series leaves a gap after it, which counts as lost only once that series has stayed quiet for
// kQuiet of the source's messages: had it been another publisher's, it would have gone on. (So a
// gap is told kQuiet messages late, and one in the source's last kQuiet messages is never told.)
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace marble_maze_ros {

class SeqGaps {
 public:
  /// Messages from a source before a gap's series counts as ended: long enough for another
  /// publisher's interleaved burst, short enough to report a loss within about 2 s at 55 Hz.
  static constexpr std::uint64_t kQuiet = 100;
  /// A series quiet this long has ended: it is forgotten, as is the least heard beyond
  /// kMostSeries a source or kMostSources sources, so that memory stays bounded.
  static constexpr std::uint64_t kForget = 2 * kQuiet;
  static constexpr std::size_t kMostSeries = 16;
  static constexpr std::size_t kMostSources = 64;

  /// Takes the seq of a message from `source`; returns how many messages it shows lost: the gaps
  /// that opened kQuiet messages of the source before it.
  std::uint64_t take(const std::string& source, std::uint32_t seq);

  std::size_t sources() const { return sources_.size(); }

 private:
  struct Series {
    std::uint32_t last;        // its latest seq
    std::uint64_t heard;       // the source's count of messages when it was last continued
    std::uint64_t gap = 0;     // messages missing before its first, if it follows `before`
    std::uint32_t before = 0;  // the last seq of the series it may follow
    std::uint64_t due = 0;     // the source's count at which the gap is judged
    bool ended = false;        // merged into the series after its gap
  };
  struct Source {
    std::vector<Series> series;
    std::uint64_t count = 0;  // messages taken from it
    std::uint64_t heard = 0;  // all sources' count when it was last heard
  };

  Source& sourceNamed(const std::string& name);
  static std::uint64_t judgeGaps(Source* source);
  static void forgetEnded(Source* source);

  std::map<std::string, Source> sources_;
  std::uint64_t count_ = 0;  // messages taken from all sources
};

}  // namespace marble_maze_ros
