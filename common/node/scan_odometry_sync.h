#pragma once
// Pairs scans with odometry as they arrive on the bus (live or replayed from a log), for
// every process that needs the odometry pose at a scan's utime (the pose estimators, the
// contour mapper):
//   * a scan waits until an odometry reading at or after its utime has arrived, so its pose
//     is interpolated rather than extrapolated; at shutdown the waiting scans take the
//     newest reading if it is close enough;
//   * the odometry history covers the last 60 s (history_us);
//   * odometry whose time goes back (a log restarted, a simulator reset) clears the history;
//     a reading more than jump_us before or after the newest one (a stamp of INT64_MAX, or
//     of 0 in a live stream) is believed only when restart_confirmations more readings
//     follow it in order: a lone reading far off is rejected (counted), so one hostile
//     or corrupt message can neither reset the history nor hold it up;
//   * a scan stamped more than max_scan_lead_us after the newest reading does not wait for
//     odometry that may never come: it is released at once, without odometry;
//   * at most max_pending scans wait: beyond that the oldest is dropped (and counted).
// Scans come out in arrival order. Plain C++: the node converts messages and logs.

#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "common/pose2.h"
#include "common/scan.h"
#include "common/vehicle_state.h"

namespace minenav {

struct ScanOdometrySyncOptions {
  // us; farthest odometry reading from a scan's utime that may serve for it.
  int64_t max_odometry_gap_us = 1'000'000;
  // us; odometry older than this before the newest reading is forgotten.
  int64_t history_us = 60'000'000;
  // Scans that may wait for odometry; beyond this the oldest is dropped.
  size_t max_pending = 100;
  // us; a reading this far from the newest one needs confirmation (see above).
  int64_t jump_us = 60'000'000;
  // Readings in order after a far-off one that make it a restart of the stream.
  int restart_confirmations = 2;
  // us; a scan further ahead of the newest reading than this is released without odometry.
  int64_t max_scan_lead_us = 10'000'000;
};

// A scan ready to process. `odometry` is empty when no reading was within
// max_odometry_gap_us of the scan (the caller skips it with a message).
struct SyncedScan {
  LadarScan scan;
  std::optional<Pose2> odometry;
  bool exact = false;  // a reading is stamped exactly with the scan's utime
};

class ScanOdometrySync {
 public:
  explicit ScanOdometrySync(ScanOdometrySyncOptions options = {}) : options_(options) {}

  // Returns false when the reading went back in time and cleared the history (log it).
  // A far-off reading awaiting confirmation, or rejected, returns true and is counted in
  // rejected_odometry() once it is known to be alone.
  bool AddOdometry(const OdometryReading& reading);
  // Returns false when the queue was full and the oldest waiting scan was dropped.
  bool AddScan(LadarScan scan);
  // The scans that can be processed now, in arrival order (all of them at shutdown).
  std::vector<SyncedScan> TakeReady(bool at_shutdown = false);

  const std::deque<OdometryReading>& odometry() const { return odometry_; }
  size_t pending() const { return pending_.size(); }
  int64_t dropped() const { return dropped_; }
  int64_t rejected_odometry() const { return rejected_odometry_; }

 private:
  // True when `utime` is more than jump_us away from `reference` (no overflow).
  bool FarFrom(int64_t utime, int64_t reference) const;

  ScanOdometrySyncOptions options_;
  std::deque<OdometryReading> odometry_;
  std::vector<OdometryReading> restart_candidates_;  // far-off readings awaiting confirmation
  int64_t rejected_odometry_ = 0;
  std::deque<LadarScan> pending_;
  int64_t dropped_ = 0;
};

}  // namespace minenav
