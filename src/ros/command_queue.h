// Tilt commands held until their stamp and applied in stamp order. Plain C++: times are seconds.
#pragma once

#include <algorithm>
#include <cstddef>
#include <deque>

namespace marble_maze_ros {

struct TiltCommand {
  enum class Kind { Angles, Rates };
  double stamp = 0;  ///< s: apply at the first step that starts at or after it
  Kind kind = Kind::Angles;
  double roll = 0;   ///< rad (Angles) or rad/s (Rates)
  double pitch = 0;  ///< rad (Angles) or rad/s (Rates)
};

class CommandQueue {
 public:
  /// Keeps the queue in stamp order; equal stamps stay in arrival order. Returns false, dropping
  /// the command stamped furthest ahead (the least urgent), when the queue was full.
  bool push(const TiltCommand& command) {
    const auto later = std::upper_bound(
        queue_.begin(), queue_.end(), command.stamp,
        [](double stamp, const TiltCommand& queued) { return stamp < queued.stamp; });
    queue_.insert(later, command);
    if (queue_.size() <= kCapacity) return true;
    queue_.pop_back();
    return false;
  }

  /// Hands every command stamped at or before `time` to `apply`, in stamp order, and drops them.
  template <typename Apply>
  void applyDue(double time, Apply apply) {
    while (!queue_.empty() && queue_.front().stamp <= time) {
      apply(queue_.front());
      queue_.pop_front();
    }
  }

  void clear() { queue_.clear(); }
  std::size_t size() const { return queue_.size(); }

 private:
  static constexpr std::size_t kCapacity = 10000;
  std::deque<TiltCommand> queue_;
};

}  // namespace marble_maze_ros
