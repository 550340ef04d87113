#pragma once
// MappingSession: the policy of one mapping run, shared by the batch tool and the live
// contour_mapper process so that replaying a log live gives the batch map by construction
// (thesis 4.1.2 cycle, 4.7 concurrent refinement; DESIGN.md "Every process also runs in
// batch ... gives the same answer").
//
// It holds a ContourMapper and takes scans with the odometry pose at each scan's utime:
//   * initial estimate = the odometry motion since the last accepted scan composed onto that
//     scan's estimated pose (the first scan: its odometry pose). Using odometry poses directly
//     would carry the first scan's error as a frame offset growing with distance from it.
//   * insertion policy for robots that scan while they move (CARMEN-style 180° scans at
//     5-10 Hz): a scan is INSERTED only when the vehicle moved insert_min_translation or
//     turned insert_min_rotation since the last inserted scan (by its initial estimate);
//     other scans are TRACKED: their pose is estimated against the contours and reported,
//     the map is not touched. Defaults 0/0 insert every scan (the survey case).
//   * periodic concurrent refinement every refine_every_inserts inserts (0 = only when the
//     caller asks, e.g. at the end), at a deterministic point in the scan sequence.
//   * a scan that does not fit is REFUSED with a one-line reason; the map is left unchanged.
// Plain C++, no LCM, no clock, no threads.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/file_io.h"
#include "common/match_result.h"
#include "common/pose2.h"
#include "common/scan.h"
#include "mapper/contour_mapper.h"

namespace minenav::mapper {

struct MappingSessionOptions {
  ContourMapperOptions mapper;
  // m; insert a scan when the vehicle moved at least this far since the last inserted scan
  // (0 = this criterion is off). With both criteria off every scan is inserted.
  double insert_min_translation = 0.0;
  // rad; insert a scan when the heading changed at least this much since the last inserted
  // scan (0 = off).
  double insert_min_rotation = 0.0;
  // Run concurrent refinement (mapper.refinement) after every this many inserts (0 = never;
  // call Refine() instead).
  int refine_every_inserts = 0;
};

std::string ValidateOptions(const MappingSessionOptions& options);
// Declares every field of `o` under `scope` (unit, default, range, why): config keys and flags.
void DeclareOptions(OptionScope scope, MappingSessionOptions& o);

enum class ScanOutcome { kInserted, kTracked, kRefused };
const char* ToString(ScanOutcome outcome);

// One scan's outcome. Its core (common/match_result.h) is what the contour_mapper process
// publishes on POSE: pose = the estimate (the initial pose when refused); converged = the
// scan was accepted (inserted or tracked); status = "ok: inserted", "ok: tracked" or why it
// was refused; num_points = usable points after preprocessing; num_inliers = points
// matching the contours at the estimate; iterations = of the pose estimation; residual = m,
// RMS distance to the matched contours at the estimate; covariance stays zero.
struct ScanResult : MatchResult {
  ScanOutcome outcome = ScanOutcome::kRefused;
  std::string summary;      // accepted: what the estimate and the insert did; else empty
  int64_t utime = 0;        // the scan's
  int64_t scan_id = 0;
  Pose2 initial;            // world_T_vehicle the estimate started from
  int scan_index = -1;      // index in mapper().scans() when inserted
  bool refined = false;     // a periodic concurrent refinement ran after this scan
  ConcurrentRefinementResult refinement;
  bool accepted() const { return outcome != ScanOutcome::kRefused; }
};

// One row of the poses output: an inserted (scan_index >= 0) or tracked scan.
struct SessionPose {
  int64_t utime = 0;
  int scan_index = -1;  // inserted scans report their current (refined) pose
  Pose2 pose;           // tracked scans: the estimate
};

// What the session holds beside the mapper (saved in checkpoints, map_checkpoint.h).
struct MappingSessionState {
  bool has_anchor = false;       // an accepted scan exists
  Pose2 anchor_pose;             // estimated pose of the last accepted scan
  Pose2 anchor_odometry;         // its odometry pose
  int anchor_scan_index = -1;    // >= 0 when it was inserted (refinement moves it)
  int inserts_since_refine = 0;
  int64_t inserted = 0, tracked = 0, refused = 0;
  std::vector<SessionPose> poses;  // in arrival order
};

class MappingSession {
 public:
  explicit MappingSession(MappingSessionOptions options = {});
  // Starts from a saved contour map (--load-map): the first scan is localised against it
  // and then anchors the frame at that estimate.
  MappingSession(MappingSessionOptions options, ContourMap map);
  // Resumes a checkpoint: the mapper's map and scans and the session state.
  MappingSession(MappingSessionOptions options, ContourMap map, std::vector<MappedScan> scans,
                 MappingSessionState state);

  // One scan with the odometry pose (odometry frame) at its utime.
  ScanResult AddScan(const LadarScan& scan, const Pose2& odometry);
  // Concurrent refinement of every inserted pose and contour (4.7); the periodic one of
  // AddScan too stops early when options().mapper.refinement.should_stop says so (a stopped
  // refinement leaves the state as after its last kept round and does not count as done).
  ConcurrentRefinementResult Refine();
  // The same with another stop test in place of the options' (empty: run to the end).
  ConcurrentRefinementResult Refine(const ShouldStop& should_stop);
  // The same with other refinement options in place of options().mapper.refinement.
  ConcurrentRefinementResult RefineWith(const ConcurrentRefinementOptions& refinement);

  const MappingSessionOptions& options() const { return options_; }
  const ContourMapper& mapper() const { return mapper_; }
  const ContourMap& map() const { return mapper_.map(); }
  const MappingSessionState& state() const { return state_; }
  // Every inserted or tracked scan's pose, keyed by its utime, in arrival order (inserted
  // scans at their current estimate).
  std::vector<StampedPose> Poses() const;

 private:
  ScanResult Track(PreprocessedScan scan, ScanResult out) const;
  ConcurrentRefinementResult AfterRefine(ConcurrentRefinementResult r);

  MappingSessionOptions options_;
  ContourMapper mapper_;
  MappingSessionState state_;
};

}  // namespace minenav::mapper
