#pragma once
// The pose at a given time from a time-sorted sequence of stamped poses (odometry, truth,
// estimates): the exact reading, else interpolated between the two around it, else the
// nearest one at the ends when it is within max_gap_us. Works on any container of
// readings with `utime` (us) and `pose` members (OdometryReading, TruthReading,
// StampedPose).

#include <algorithm>
#include <cstdint>
#include <optional>

#include "common/pose2.h"

namespace minenav {

// later - earlier for later >= earlier, exact for any two int64 times (a hostile stamp
// such as INT64_MIN must not overflow the subtraction and defeat a gap limit).
inline uint64_t TimeGap(int64_t later, int64_t earlier) {
  return static_cast<uint64_t>(later) - static_cast<uint64_t>(earlier);
}

template <typename Readings>
std::optional<Pose2> PoseAtTime(const Readings& readings, int64_t utime, int64_t max_gap_us) {
  if (readings.empty()) return std::nullopt;
  const auto after = std::lower_bound(readings.begin(), readings.end(), utime,
                                      [](const auto& r, int64_t t) { return r.utime < t; });
  if (after != readings.end() && after->utime == utime) return after->pose;
  const auto max_gap = static_cast<uint64_t>(std::max<int64_t>(0, max_gap_us));
  if (after == readings.end()) {
    if (TimeGap(utime, std::prev(after)->utime) > max_gap) return std::nullopt;
    return std::prev(after)->pose;
  }
  if (after == readings.begin()) {
    if (TimeGap(after->utime, utime) > max_gap) return std::nullopt;
    return after->pose;
  }
  const auto& a = *std::prev(after);
  const auto& b = *after;
  // Between two readings the gap may be twice max_gap: each is then within max_gap of
  // the middle.
  if (TimeGap(b.utime, a.utime) > 2 * max_gap) return std::nullopt;
  const double f = static_cast<double>(TimeGap(utime, a.utime)) / static_cast<double>(TimeGap(b.utime, a.utime));
  return InterpolatePose(a.pose, b.pose, f);
}

// True when a reading is stamped exactly `utime`.
template <typename Readings>
bool HasReadingAt(const Readings& readings, int64_t utime) {
  const auto it = std::lower_bound(readings.begin(), readings.end(), utime,
                                   [](const auto& r, int64_t t) { return r.utime < t; });
  return it != readings.end() && it->utime == utime;
}

}  // namespace minenav
