#pragma once
// Many scans matched to each other simultaneously (thesis 3.5, A.3): every point of every
// scan is paired with the nearest segment of the other scans' raw polylines, and all poses
// except the fixed ones move together by Gauss-Newton. Where the thesis inverted the dense
// 3N x 3N matrix (O(N^3), 3.5), the normal equations here are assembled as a sparse block
// matrix (only overlapping scans share a block) and solved with Eigen's SimplicialLDLT.
//
// Each scan's lookup table is built once in its own frame; points of scan m are carried
// into scan n's frame with the current poses, so tables never need rebuilding.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "common/pose2.h"
#include "pose_estimator/iconic/iconic_matcher.h"
#include "pose_estimator/iconic/scan_polylines.h"

namespace minenav {

struct MultiScanOptions {
  IconicMatchOptions match;     // thresholds, loss, iterations (its epsilons are not used)
  // Converged when no pose moves more than these (m, rad). Looser than one scan's: points
  // hop between overlapping scans' polylines, so the step jitters at ~0.3 mm. Defaults
  // 1 mm and 1e-4 rad.
  double epsilon_translation = 1e-3;
  double epsilon_rotation = 1e-4;
  PartialScanOptions partial;   // how scans become polylines
  // Lookup table cells of each scan's table (m). Default 0.1 m: raw scan segments are a few
  // cm long, and the automatic (finer) size makes queries faster but builds much slower.
  double cell_size = 0.1;
  // Scans whose initial positions are farther apart than this are never paired (m).
  // Default 60 m: beyond twice the useful range two scans cannot overlap.
  double max_pair_distance = 60.0;
  // true: a point gives one residual for every other scan with a segment within the
  // threshold (each scan pair is its own term, as A.3 writes it); false: only for the
  // scan with the nearest segment (3.4's "taking the minimum distance"). Default true:
  // picking the nearest of several noisy polylines biases each link by ~1 cm along the
  // weakly constrained direction, which adds up along a chain (10 cm over 10 mine scans,
  // < 1 cm with every pair).
  bool every_overlapping_scan = true;
  // Every k-th point of a scan is used as a query (1 = all). Default 1.
  int point_stride = 1;
};

class OptionScope;
// Declares every field of MultiScanOptions under `scope`; match and partial nest.
void DeclareOptions(OptionScope scope, MultiScanOptions& o);
// The adjustment's own parameters (not match, partial or the table's cell) wherever they are
// kept: in MultiScanOptions, and in IconicEstimatorOptions, which hands its copies on.
// Declared in one place so that both say the same.
struct MultiScanParameters {
  double* epsilon_translation;
  double* epsilon_rotation;
  double* max_pair_distance;
  bool* every_overlapping_scan;
  int* point_stride;
};
void DeclareMultiScanParameters(OptionScope scope, const MultiScanParameters& p);

struct MultiScanInput {
  std::vector<Eigen::Vector2d> points;  // vehicle frame, in scan order
  Pose2 initial;                        // map frame
  bool fixed = false;                   // at least one scan must be fixed
};

struct MultiScanResult {
  std::vector<Pose2> poses;               // one per input scan (fixed ones unchanged)
  std::vector<Eigen::Matrix3d> covariances;  // marginal 3x3 per scan; zero for fixed ones
  std::vector<int> inliers;               // matched points per scan at the end
  double residual = 0.0;                  // m, RMS over all pairs at the end
  int num_inliers = 0;
  int iterations = 0;
  double final_threshold = 0.0;
  double solve_seconds = 0.0;             // time in the sparse factorisations
  bool converged = false;
  std::string status = "not run";
};

MultiScanResult MatchScansSimultaneously(const std::vector<MultiScanInput>& scans, const MultiScanOptions& options);

}  // namespace minenav
