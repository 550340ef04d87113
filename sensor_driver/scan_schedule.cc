#include "sensor_driver/scan_schedule.h"

#include <limits>

#include "common/config.h"
#include "common/pose_at_time.h"

namespace minenav {

namespace {
constexpr int64_t kNoGapLimit = std::numeric_limits<int64_t>::max() / 4;
}  // namespace

std::vector<DueScan> ScanSchedule::AddTruth(const TruthReading& t, ScheduleNote* note) {
  ScheduleNote local;
  ScheduleNote& n = note != nullptr ? *note : local;
  n = ScheduleNote{};
  std::vector<DueScan> due;
  if (!truth_.empty() && t.utime <= truth_.back().utime) {
    if (t.utime == truth_.back().utime) {
      n.duplicate = true;
      return due;
    }
    n.restarted = true;
    n.went_back_us = static_cast<int64_t>(TimeGap(truth_.back().utime, t.utime));
    truth_.clear();
    next_scan_.reset();
  }
  if (!truth_.empty() && next_scan_ && TimeGap(t.utime, truth_.back().utime) > static_cast<uint64_t>(options_.max_gap_us)) {
    // Never interpolate across a long gap: skip to the first scan time after it.
    const int64_t missed = (t.utime - *next_scan_) / options_.period_us;
    if (missed > 0) {
      n.skipped_scans = missed;
      n.gap_us = t.utime - truth_.back().utime;
      *next_scan_ += missed * options_.period_us;
    }
  }
  truth_.push_back(t);
  while (truth_.size() > 2 && TimeGap(t.utime, truth_.front().utime) > static_cast<uint64_t>(options_.history_us))
    truth_.pop_front();
  if (!next_scan_) next_scan_ = t.utime;
  while (*next_scan_ <= t.utime) {
    const int64_t scan_utime = *next_scan_;
    *next_scan_ += options_.period_us;
    // Always between the two samples around it (the scan times inside a long gap were
    // skipped above; the one just before the sample that ended the gap is interpolated).
    const std::optional<Pose2> pose = PoseAtTime(truth_, scan_utime, kNoGapLimit);
    if (pose) due.push_back({scan_utime, *pose});
  }
  return due;
}

void DeclareOptions(OptionScope scope, ScanScheduleOptions& o) {
  scope.AddMicroseconds("history", &o.history_us,
                        "how much truth history is kept for interpolating the pose at a scan's time (5 s: many "
                        "truth periods, in case samples arrive late)",
                        0.1, 600.0);
  scope.AddMicroseconds("max_gap", &o.max_gap_us,
                        "a gap between truth samples longer than this skips the scans in it instead of "
                        "interpolating across it (1 s: the vehicle may have done anything)",
                        0.01, 60.0);
}

}  // namespace minenav
