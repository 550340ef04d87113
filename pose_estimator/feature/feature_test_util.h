#pragma once
// Test helpers for the feature-based estimator: tiny worlds and exact (or noisy) scans
// ray-cast with common/geometry.h CastRay.
#include <cmath>
#include <random>
#include <vector>

#include "common/angle.h"
#include "common/geometry.h"
#include "common/pose2.h"
#include "common/scan.h"

namespace minenav::testing {

inline void AddBox(std::vector<Segment>* s, double x0, double y0, double x1, double y1) {
  s->emplace_back(x0, y0, x1, y0);
  s->emplace_back(x1, y0, x1, y1);
  s->emplace_back(x1, y1, x0, y1);
  s->emplace_back(x0, y1, x0, y0);
}

// A 12 x 8 m room with a 1 x 1 m pillar at (7..8, 3..4) and an L-shaped alcove.
inline std::vector<Segment> RoomWithPillar() {
  std::vector<Segment> s = {{0, 0, 12, 0}, {12, 0, 12, 5}, {12, 5, 10, 5}, {10, 5, 10, 8},
                            {10, 8, 0, 8}, {0, 8, 0, 0}};
  AddBox(&s, 7, 3, 8, 4);
  return s;
}

// A scan of `world` from map_T_vehicle with the sensor at sensor_offset; Gaussian range
// noise of sigma (0 = exact), readings beyond max_range are NaN.
inline LadarScan SimulateScan(const std::vector<Segment>& world, const Pose2& map_T_vehicle,
                              int num_points = 1000, double sigma = 0.0, unsigned seed = 1,
                              const Pose2& sensor_offset = Pose2(), double max_range = 50.0) {
  LadarScan scan;
  scan.utime = 1;
  scan.sensor_id = "test";
  scan.sensor_offset = sensor_offset;
  scan.start_angle = -kPi;
  scan.angle_step = 2.0 * kPi / num_points;
  scan.min_range = 0.1;
  scan.max_range = max_range;
  const Pose2 sensor = map_T_vehicle * sensor_offset;
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma > 0.0 ? sigma : 1.0);
  for (int i = 0; i < num_points; ++i) {
    const auto hit = CastRay(sensor.translation(), sensor.theta + scan.Bearing(static_cast<size_t>(i)),
                             world, max_range);
    double r = hit ? hit->range : std::nan("");
    if (hit && sigma > 0.0) r += noise(rng);
    scan.ranges.push_back(static_cast<float>(r));
  }
  return scan;
}

}  // namespace minenav::testing
