#include "seq_gaps.h"

#include <algorithm>

namespace marble_maze_ros {

SeqGaps::Source& SeqGaps::sourceNamed(const std::string& name) {
  auto it = sources_.find(name);
  if (it != sources_.end()) return it->second;
  if (sources_.size() >= kMostSources)  // a new one pushes out the least recently heard
    sources_.erase(std::min_element(sources_.begin(), sources_.end(), [](auto& a, auto& b) {
      return a.second.heard < b.second.heard;
    }));
  return sources_[name];
}

std::uint64_t SeqGaps::judgeGaps(Source* source) {
  std::uint64_t lost = 0;
  auto& all = source->series;
  for (Series& s : all) {
    if (s.gap == 0 || source->count < s.due) continue;
    // The series before the gap is still where it was: the same publisher went on past the gap,
    // and the two are one series. Had it gone on (or been forgotten), the gap is no loss.
    const auto before = std::find_if(all.begin(), all.end(), [&](const Series& p) {
      return &p != &s && !p.ended && p.last == s.before;
    });
    if (before != all.end()) {
      lost += s.gap;
      before->ended = true;  // s goes on from it
    }
    s.gap = 0;
  }
  return lost;
}

void SeqGaps::forgetEnded(Source* source) {
  auto& all = source->series;
  const std::uint64_t now = source->count;
  all.erase(std::remove_if(all.begin(), all.end(),
                           [&](const Series& s) { return s.ended || now - s.heard > kForget; }),
            all.end());
  while (all.size() > kMostSeries)
    all.erase(std::min_element(all.begin(), all.end(),
                               [](const Series& a, const Series& b) { return a.heard < b.heard; }));
}

std::uint64_t SeqGaps::take(const std::string& name, std::uint32_t seq) {
  Source& source = sourceNamed(name);
  source.heard = ++count_;
  const std::uint64_t now = ++source.count;
  auto& all = source.series;
  // The message continues a series (or repeats its last: a publisher that leaves seq alone).
  const auto continued = std::find_if(all.begin(), all.end(), [&](const Series& s) {
    return !s.ended && (s.last == seq || s.last + 1 == seq);
  });
  if (continued != all.end()) {
    continued->last = seq;
    continued->heard = now;
  } else {
    // It starts a series, after a gap from the nearest series below it, if any.
    Series fresh{seq, now};
    const Series* below = nullptr;
    for (const Series& s : all)
      if (!s.ended && s.last < seq && (!below || s.last > below->last)) below = &s;
    if (below) {
      fresh.gap = seq - below->last - 1;
      fresh.before = below->last;
      fresh.due = now + kQuiet;
    }
    all.push_back(fresh);
  }
  // Judged once the message has gone to its series: one that continues the series before a gap
  // on the very message the gap is judged at shows it was no loss.
  const std::uint64_t lost = judgeGaps(&source);
  forgetEnded(&source);
  return lost;
}

}  // namespace marble_maze_ros
