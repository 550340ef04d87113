#include "common/node/scan_odometry_sync.h"

#include <utility>

#include "common/pose_at_time.h"

namespace minenav {

bool ScanOdometrySync::FarFrom(int64_t utime, int64_t reference) const {
  // |utime - reference| > jump_us, computed without signed overflow.
  const uint64_t gap = utime >= reference ? TimeGap(utime, reference) : TimeGap(reference, utime);
  return gap > static_cast<uint64_t>(options_.jump_us);
}

bool ScanOdometrySync::AddOdometry(const OdometryReading& reading) {
  if (!odometry_.empty() && FarFrom(reading.utime, odometry_.back().utime)) {
    // A reading far from the history: the start of a new stream only if more follow it.
    const bool continues = !restart_candidates_.empty() && reading.utime > restart_candidates_.back().utime &&
                           !FarFrom(reading.utime, restart_candidates_.back().utime);
    if (!continues) {
      rejected_odometry_ += static_cast<int64_t>(restart_candidates_.size());
      restart_candidates_.clear();
    }
    restart_candidates_.push_back(reading);
    if (static_cast<int>(restart_candidates_.size()) <= options_.restart_confirmations) return true;
    odometry_.assign(restart_candidates_.begin(), restart_candidates_.end());
    restart_candidates_.clear();
    return false;
  }
  // Back in the history's window: the far-off candidates were alone.
  rejected_odometry_ += static_cast<int64_t>(restart_candidates_.size());
  restart_candidates_.clear();
  bool kept_history = true;
  if (!odometry_.empty() && reading.utime < odometry_.back().utime) {
    odometry_.clear();
    kept_history = false;
  }
  odometry_.push_back(reading);
  while (odometry_.size() > 2 && TimeGap(reading.utime, odometry_.front().utime) > static_cast<uint64_t>(options_.history_us))
    odometry_.pop_front();
  return kept_history;
}

bool ScanOdometrySync::AddScan(LadarScan scan) {
  pending_.push_back(std::move(scan));
  if (pending_.size() > options_.max_pending) {
    pending_.pop_front();
    ++dropped_;
    return false;
  }
  return true;
}

std::vector<SyncedScan> ScanOdometrySync::TakeReady(bool at_shutdown) {
  std::vector<SyncedScan> ready;
  while (!pending_.empty()) {
    const int64_t utime = pending_.front().utime;
    const bool have_later = !odometry_.empty() && odometry_.back().utime >= utime;
    // A scan stamped far beyond the odometry would block every scan behind it.
    const bool hopeless = !odometry_.empty() && utime > odometry_.back().utime &&
                          TimeGap(utime, odometry_.back().utime) > static_cast<uint64_t>(options_.max_scan_lead_us);
    if (!have_later && !hopeless && !at_shutdown) break;  // wait for odometry
    SyncedScan s;
    s.odometry = PoseAtTime(odometry_, utime, options_.max_odometry_gap_us);
    s.exact = HasReadingAt(odometry_, utime);
    s.scan = std::move(pending_.front());
    pending_.pop_front();
    ready.push_back(std::move(s));
  }
  return ready;
}

}  // namespace minenav
