#pragma once
// Test helpers (tests and benches only): tiny inline worlds and exact ray-cast scans from
// common/geometry.h CastRay, with optional Gaussian range noise.

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "common/angle.h"
#include "common/geometry.h"
#include "common/scan.h"
#include "mapper/contour_map.h"

namespace minenav::mapper::testing {

struct ScanSpec {
  int num_points = 720;
  double min_range = 0.5;      // m
  double max_range = 40.0;     // m
  double range_sigma = 0.0;    // m
  unsigned seed = 1;
  bool clockwise = false;      // negative angle_step
};

// A scan taken by a vehicle at world_T_vehicle (sensor at the vehicle origin).
inline LadarScan MakeScan(const std::vector<Segment>& world, const Pose2& world_T_vehicle,
                          const ScanSpec& spec = {}) {
  LadarScan scan;
  scan.min_range = spec.min_range;
  scan.max_range = spec.max_range;
  scan.angle_step = (spec.clockwise ? -1.0 : 1.0) * 2.0 * kPi / spec.num_points;
  scan.start_angle = spec.clockwise ? kPi : -kPi;
  std::mt19937 rng(spec.seed);
  std::normal_distribution<double> noise(0.0, spec.range_sigma > 0.0 ? spec.range_sigma : 1.0);
  scan.ranges.resize(static_cast<size_t>(spec.num_points));
  for (int i = 0; i < spec.num_points; ++i) {
    const double bearing = world_T_vehicle.theta + scan.Bearing(static_cast<size_t>(i));
    const auto hit = CastRay(world_T_vehicle.translation(), bearing, world, spec.max_range);
    double r = hit ? hit->range : std::nan("");
    if (hit && spec.range_sigma > 0.0) r += noise(rng);
    scan.ranges[static_cast<size_t>(i)] = static_cast<float>(r);
  }
  return scan;
}

// Axis-aligned rectangle as four segments, counter-clockwise (interior on the left).
inline std::vector<Segment> Rectangle(double x0, double y0, double x1, double y1) {
  return {Segment(x0, y0, x1, y0), Segment(x1, y0, x1, y1), Segment(x1, y1, x0, y1), Segment(x0, y1, x0, y0)};
}

inline std::vector<Segment> Concat(std::vector<Segment> a, const std::vector<Segment>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// A 20 x 12 m room with two pillars: asymmetric enough that poses are well constrained.
inline std::vector<Segment> SmallRoomWorld() {
  std::vector<Segment> w = Rectangle(0, 0, 20, 12);
  w = Concat(w, Rectangle(5, 4, 7, 7));
  w = Concat(w, Rectangle(12, 3, 15, 5));
  return w;
}

// A 720-point scan of SmallRoomWorld at `truth` with 2 cm range noise, stamped `utime` (us)
// and scan_id utime / 1000: the scans of the mapping-session and checkpoint tests.
inline LadarScan NoisySmallRoomScan(const Pose2& truth, unsigned seed, int64_t utime) {
  ScanSpec spec;
  spec.num_points = 720;
  spec.range_sigma = 0.02;
  spec.seed = seed;
  LadarScan scan = MakeScan(SmallRoomWorld(), truth, spec);
  scan.utime = utime;
  scan.scan_id = utime / 1000;
  return scan;
}

// A loop: corridors 5 m wide around a 12 x 6 m block of pillars, with crib blocks along
// the outer walls so no corridor is featureless within a short range.
inline std::vector<Segment> LoopWorld() {
  std::vector<Segment> w = Rectangle(0, 0, 22, 16);
  w = Concat(w, Rectangle(5, 5, 17, 11));
  const double cribs[][2] = {{4, 0.3}, {11, 0.3}, {18, 0.3}, {21.1, 5}, {21.1, 11}, {15, 15.1}, {7, 15.1}, {0.3, 8}};
  for (const auto& c : cribs) w = Concat(w, Rectangle(c[0], c[1], c[0] + 0.6, c[1] + 0.6));
  return w;
}

// Stations around the loop's centre line, counter-clockwise.
inline std::vector<Pose2> LoopStations() {
  return {{2.5, 2.5, 0.0},   {8.5, 2.5, 0.0},   {14.5, 2.5, 0.0},  {19.5, 2.5, 1.57}, {19.5, 8.0, 1.57},
          {19.5, 13.5, 3.14}, {13.5, 13.5, 3.14}, {7.5, 13.5, 3.14}, {2.5, 13.5, -1.57}, {2.5, 8.0, -1.57}};
}

// Odometry that drifts: each step's true motion with a 2 % scale error and a small turn
// bias, accumulated from the first true pose (the odometry frame is the world frame at start).
inline std::vector<Pose2> DriftingOdometry(const std::vector<Pose2>& truth) {
  std::vector<Pose2> odo{truth.front()};
  for (size_t k = 1; k < truth.size(); ++k) {
    const Pose2 step = Between(truth[k - 1], truth[k]);
    odo.push_back(odo.back() * Pose2(1.02 * step.x, 1.02 * step.y, step.theta + 0.004));
  }
  return odo;
}

// The true contours of SmallRoomWorld, oriented with free space on the left: the room
// counter-clockwise, the pillars clockwise; vertices every `nominal` metres.
inline ContourMap SmallRoomContours(double nominal = 0.5) {
  ContourMap map;
  auto add = [&](std::vector<Eigen::Vector2d> corners, bool free_inside) {
    if (!free_inside) std::reverse(corners.begin(), corners.end());
    map.Create(ResamplePolyline(corners, true, nominal), true);
  };
  add({{0, 0}, {20, 0}, {20, 12}, {0, 12}}, true);
  add({{5, 4}, {7, 4}, {7, 7}, {5, 7}}, false);
  add({{12, 3}, {15, 3}, {15, 5}, {12, 5}}, false);
  return map;
}

}  // namespace minenav::mapper::testing
