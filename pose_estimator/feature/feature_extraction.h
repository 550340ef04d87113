#pragma once
// Feature extraction (thesis 2.1.4): reduces a scan to an ordered list of corners and
// line segments in the sensor frame.
//   1. Break the scan into pieces where successive points are far apart (occlusions) or
//      readings are missing; drop pieces with only a few points.
//   2. Slide the corner operator (corner_operator.h) along each piece.
//   3. Fit a line to the points between neighbouring corners (or piece ends). The fit
//      drops points farther than outlier_factor * noise_sigma from the line and refits,
//      so clutter against a wall does not bend the line; a run of consecutive points off
//      the line (a small column jutting out) splits the span into two lines; a span that
//      is not straight (curved rib, rubble) gives no line.
//   4. A corner between two fitted lines is moved to their intersection (hundreds of
//      points instead of one arm's worth). The visible end of a piece that hides something
//      farther, or open space, is an occlusion corner (arms: the line, the ray).
#include <vector>

#include "common/scan.h"
#include "pose_estimator/feature/corner_operator.h"
#include "pose_estimator/feature/feature_types.h"

namespace minenav {

struct ExtractionOptions {
  double break_distance = 0.3;        // m, gap between successive points that breaks the scan
  double break_range_factor = 0.05;   // 1, plus this fraction of the range (grazing walls)
  int min_piece_points = 6;           // smaller pieces are thrown out
  CornerOperatorOptions corner;       // the corner operator
  double noise_sigma = 0.1;           // m, range noise of the sensor (Cyclone ~0.1)
  double outlier_factor = 3.0;        // 1, line fits drop points beyond this many sigma
  double corner_gap = 0.15;           // m, points this close to a corner stay out of line fits
  int min_line_points = 8;            // points a line needs (after dropping outliers)
  int split_run_points = 3;           // a run of this many points off a line splits it
  double min_line_length = 0.5;       // m, shorter lines are not features
  double max_line_rms = 0.13;         // m, RMS of the line fit after dropping outliers (~1.3 sigma)
  double min_inlier_fraction = 0.7;   // 1, of the span's points that must lie on the line
  bool occlusion_corners = true;      // report occlusion corners at occluding piece ends
};

class OptionScope;
// Declares every field of ExtractionOptions under `scope` (unit, meaning, range).
void DeclareOptions(OptionScope scope, ExtractionOptions& o);

struct ExtractedFeatures {
  std::vector<Feature> features;  // sensor frame, ordered by azimuth
  int num_points = 0;             // valid readings
  int num_pieces = 0;             // pieces kept after breaking
};

ExtractedFeatures ExtractFeatures(const LadarScan& scan, const ExtractionOptions& options = {});

}  // namespace minenav
