#pragma once
// Pairs scans with odometry as they arrive on the bus (live or replayed from a log), for
// every process that needs the odometry pose at a scan's utime (the pose estimators, the
// contour mapper):
//   * a scan waits until an odometry reading at or after its utime has arrived, so its pose
//     is interpolated rather than extrapolated; at shutdown the waiting scans take the
//     newest reading if it is close enough;
//   * the odometry history covers the last 60 s (history_us);
//   * odometry whose time goes back (a log restarted, a simulator reset) clears the history;
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
  bool AddOdometry(const OdometryReading& reading);
  // Returns false when the queue was full and the oldest waiting scan was dropped.
  bool AddScan(LadarScan scan);
  // The scans that can be processed now, in arrival order (all of them at shutdown).
  std::vector<SyncedScan> TakeReady(bool at_shutdown = false);

  const std::deque<OdometryReading>& odometry() const { return odometry_; }
  size_t pending() const { return pending_.size(); }
  int64_t dropped() const { return dropped_; }

 private:
  ScanOdometrySyncOptions options_;
  std::deque<OdometryReading> odometry_;
  std::deque<LadarScan> pending_;
  int64_t dropped_ = 0;
};

}  // namespace minenav
