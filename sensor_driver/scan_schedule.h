#pragma once
// When the simulated ladar takes its scans, on the clock of the vehicle's true pose: scan k
// is stamped t0 + k * period (t0 = the first truth sample) and is due as soon as a truth
// sample at or after that time has arrived; its pose is interpolated between the two
// samples around it (common/pose_at_time.h), never extrapolated. So a batch run over a log
// of SIM_TRUTH makes exactly the scans the live run made.
//   - a gap in the truth stream longer than max_gap skips the scan times inside it;
//   - truth going back in time (the simulator restarted) starts a new schedule;
//   - a repeated sample is ignored.
// Plain C++: the node feeds samples and casts the scans it returns.

#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "common/pose2.h"
#include "common/vehicle_state.h"

namespace minenav {

struct ScanScheduleOptions {
  int64_t period_us = 100'000;     // between scans (1 / scan rate)
  int64_t history_us = 5'000'000;  // truth kept for interpolation
  int64_t max_gap_us = 1'000'000;  // a longer gap between truth samples skips the scans in it
};

class OptionScope;
// Declares history_us and max_gap_us under `scope`, in seconds. period_us is not an option:
// it is 1 / the ladar model's scan rate.
void DeclareOptions(OptionScope scope, ScanScheduleOptions& o);

struct DueScan {
  int64_t utime = 0;  // the scan's stamp
  Pose2 pose;         // the true pose at that time
};

// What one truth sample did to the schedule besides the scans it made due (for the log).
struct ScheduleNote {
  bool duplicate = false;
  bool restarted = false;     // time went back: a new schedule
  int64_t went_back_us = 0;
  int64_t skipped_scans = 0;  // scan times inside a gap
  int64_t gap_us = 0;
};

class ScanSchedule {
 public:
  explicit ScanSchedule(ScanScheduleOptions options = {}) : options_(options) {}

  // Adds a truth sample and returns the scans now due, oldest first.
  std::vector<DueScan> AddTruth(const TruthReading& sample, ScheduleNote* note = nullptr);

  const std::optional<int64_t>& next_scan_utime() const { return next_scan_; }

 private:
  ScanScheduleOptions options_;
  std::deque<TruthReading> truth_;
  std::optional<int64_t> next_scan_;
};

}  // namespace minenav
