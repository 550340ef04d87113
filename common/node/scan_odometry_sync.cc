#include "common/node/scan_odometry_sync.h"

#include <utility>

#include "common/pose_at_time.h"

namespace minenav {

bool ScanOdometrySync::AddOdometry(const OdometryReading& reading) {
  bool kept_history = true;
  if (!odometry_.empty() && reading.utime < odometry_.back().utime) {
    odometry_.clear();
    kept_history = false;
  }
  odometry_.push_back(reading);
  while (odometry_.size() > 2 && odometry_.front().utime < reading.utime - options_.history_us) odometry_.pop_front();
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
    if (!have_later && !at_shutdown) break;  // wait for odometry
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
