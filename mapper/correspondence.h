#pragma once
// Correspondence between partial scans and contours (thesis 4.3.2). A scan point
// corresponds to the nearest contour segment that satisfies all three conditions:
//   1. the point lies between the perpendiculars through the segment's end points;
//   2. the sensor lies on the segment's sensed (left, contour.h) side;
//   3. the perpendicular distance is below the threshold.
// The points matched to one segment from one partial scan are then sorted along the
// segment; consecutive ones form the "pieces" the integral error (integral_error.h) is
// summed over. Candidates come from the map's segment grid, so the cost is O(N) in scan
// points for a bounded map density rather than O(N M).

#include <Eigen/Core>
#include <vector>

#include "common/pose2.h"
#include "mapper/contour_map.h"
#include "mapper/scan_preprocessing.h"

namespace minenav::mapper {

struct PointMatch {
  SegmentRef segment;     // contour -1: no correspondence
  double along = 0.0;     // m, position of the foot point from the segment start
  double distance = 0.0;  // m, signed perpendicular distance (+ on the sensed side)
  bool matched() const { return segment.contour >= 0; }
};

// Matches for each world point of one partial scan (index-aligned with `world_points`).
std::vector<PointMatch> MatchPoints(const std::vector<Eigen::Vector2d>& world_points,
                                    const Eigen::Vector2d& sensor_world, const ContourMap& map,
                                    double threshold);

// One piece of the integral error: points i < j (indices into partial scan `partial`),
// consecutive along `segment`.
struct ErrorPiece {
  int partial = 0;
  int i = 0;
  int j = 0;
  SegmentRef segment;
};

// The pieces of one partial scan from its matches: grouped by segment, sorted along it.
void AppendPieces(int partial, const std::vector<PointMatch>& matches, std::vector<ErrorPiece>* pieces);

struct ScanCorrespondence {
  std::vector<ErrorPiece> pieces;
  std::vector<std::vector<PointMatch>> matches;  // per partial scan, per point
  int num_points = 0;
  int num_matched = 0;
};

// Correspondence of every partial scan of `scan` placed at world_T_vehicle.
ScanCorrespondence CorrespondScan(const PreprocessedScan& scan, const Pose2& world_T_vehicle,
                                  const ContourMap& map, double threshold);

// The partial scan's points in the world frame.
std::vector<Eigen::Vector2d> ToWorld(const PartialScan& partial, const Pose2& world_T_vehicle);

}  // namespace minenav::mapper
