#pragma once
// The result of estimating the vehicle pose for one scan (channels POSE_FPE, POSE_IPE,
// POSE): what the matcher reported (common/match_result.h) stamped with the scan, the
// estimator and the time it took. Recoverable failures are values: converged = false with
// a one-line status.

#include <cstdint>
#include <string>
#include <utility>

#include "common/match_result.h"

namespace minenav {

struct PoseEstimate : MatchResult {
  int64_t utime = 0;    // us, the scan's utime
  int64_t scan_id = 0;
  std::string source;   // "fpe", "ipe", "clue"
  double compute_time = 0.0;  // s
};

// The one way from a matcher's result to the published estimate: every field of `match`
// as it is, with the scan's utime and id, the estimator's name and its compute time (s).
inline PoseEstimate MakePoseEstimate(const MatchResult& match, int64_t utime, int64_t scan_id, std::string source,
                                     double compute_time) {
  return PoseEstimate{match, utime, scan_id, std::move(source), compute_time};
}

}  // namespace minenav
