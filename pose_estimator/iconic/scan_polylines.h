#pragma once
// Maps made from scans (thesis 3.2-3.4). A scan is broken into "partial scans" at
// discontinuities larger than a threshold (occlusions, 3.3); each partial scan is a
// polyline through its points (variants 3-5), or a polyline fit to its points with
// segments of about 0.5 m (variant 2; the thesis fit contours, 3.2.1).

#include <Eigen/Core>
#include <vector>

#include "common/geometry.h"
#include "common/pose2.h"

namespace minenav {

struct PartialScanOptions {
  // Consecutive points farther apart than this start a new partial scan (m). Default 0.5 m:
  // well above twice the range noise (3.3), below the gaps that occlusions leave.
  double break_distance = 0.5;
  // Partial scans with fewer points are dropped as clutter or mixed pixels. Default 3.
  int min_points = 3;
};

// Splits consecutive scan points (in scan order) into partial scans (common/scan_split.h):
// NaN points are skipped, and a 360-degree scan whose last point is near its first wraps
// around, its last partial scan continuing into the first (listed first).
std::vector<std::vector<Eigen::Vector2d>> SplitIntoPartialScans(const std::vector<Eigen::Vector2d>& points,
                                                               const PartialScanOptions& options);

// The raw polylines: one segment between every pair of neighbouring points (3.3).
std::vector<Segment> PartialScansToSegments(const std::vector<std::vector<Eigen::Vector2d>>& partial_scans);

struct PolylineFitOptions {
  // Target segment length of the fit polylines (m). Default 0.5 m (3.2.1).
  double segment_length = 0.5;
};

class OptionScope;
// Declare every field of PartialScanOptions / PolylineFitOptions under `scope`.
void DeclareOptions(OptionScope scope, PartialScanOptions& o);
void DeclareOptions(OptionScope scope, PolylineFitOptions& o);

// Fits polylines to partial scans: each is cut into runs of about segment_length, a total
// least-squares line is fit to each run, and neighbouring runs meet at the mean of their
// lines' projections of the shared point. Averages range noise out of the map.
std::vector<Segment> FitPolylines(const std::vector<std::vector<Eigen::Vector2d>>& partial_scans,
                                  const PolylineFitOptions& options);

// Segments moved by a pose (frame of the scan -> map frame).
std::vector<Segment> TransformSegments(const Pose2& pose, const std::vector<Segment>& segments);

}  // namespace minenav
