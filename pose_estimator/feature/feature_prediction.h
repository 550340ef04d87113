#pragma once
// Feature prediction (thesis 2.1.3): from an approximate sensor position (x, y), the
// ordered list of map corners and line segments the scanner can see as it sweeps counter-
// clockwise, with occlusion.
//
// The thesis sorts the segment endpoints by azimuth and tests, per segment, which
// endpoints in its azimuth range it hides. We do the same with one angular sweep: the
// endpoint azimuths cut the circle into intervals in each of which one segment is nearest
// (segments do not cross); the nearest one is found among the segments whose azimuth
// range is active in the sweep. Sorting is O(N log N); the rest is the sum of the active
// set sizes, small when walls hide each other and limited by the maximum range.
// Every map vertex gets a label: visible or not, and if visible, occluding or not. A
// visible vertex where two visible segments meet is a regular corner; the visible end of a
// segment that hides something farther (or open space) is an occlusion corner.
#include <Eigen/Core>
#include <vector>

#include "pose_estimator/feature/feature_map.h"
#include "pose_estimator/feature/feature_types.h"

namespace minenav {

struct PredictionOptions {
  double max_range = 50.0;  // m, the scanner's useful range; farther map parts are ignored
  double min_line_length = 0.3;  // m, shorter visible pieces of segments are not predicted
  // rad: visible neighbours meeting at less than this bend are one line and no corner
  // (maps often split a straight wall into several segments).
  double collinear_angle = 0.035;
};

class OptionScope;
// Declares every field of PredictionOptions under `scope` (unit, meaning, range).
void DeclareOptions(OptionScope scope, PredictionOptions& o);

struct VertexLabel {
  bool visible = false;
  bool occluding = false;  // its segment hides something farther (or open space) behind it
};

struct PredictedFeatures {
  // Map frame, ordered by azimuth around the position, counter-clockwise from -pi.
  std::vector<Feature> features;
  std::vector<VertexLabel> vertex_labels;  // one per map vertex
  int segments_in_range = 0;
  std::vector<int> segments_in_range_ids;  // indices of the map segments within max_range
  std::vector<int> visible_segments;       // indices of the segments seen over some angle
};

PredictedFeatures PredictFeatures(const FeatureMap& map, const Eigen::Vector2d& position,
                                  const PredictionOptions& options = {});

}  // namespace minenav
