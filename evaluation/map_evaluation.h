#pragma once
// Measures of a contour map against ground truth (tests and benchmarks, thesis 5.2):
// deviation of the contours from the true walls, and coverage of true points.

#include <Eigen/Core>
#include <vector>

#include "common/geometry.h"
#include "mapper/contour_map.h"

namespace minenav::mapper {

struct MapDeviation {
  double mean = 0.0;  // m, mean distance of contour samples to the nearest true wall
  double max = 0.0;   // m
  int samples = 0;
  Eigen::Vector2d worst_point = Eigen::Vector2d::Zero();  // where the max occurs
  int worst_contour = -1;
};
// Samples every contour every `step` metres (and at every vertex).
MapDeviation ContourDeviation(const ContourMap& map, const std::vector<Segment>& truth, double step = 0.05);

// Fraction of `points` within `distance` of some contour segment.
double Coverage(const std::vector<Eigen::Vector2d>& points, const ContourMap& map, double distance);

}  // namespace minenav::mapper
