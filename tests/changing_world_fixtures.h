#pragma once
// Small changing worlds and exact scan checks shared by the changing-world tests (batch
// and on the bus). The checks use the brute-force CastRay of common/geometry.h as the
// reference, never the ladar's own grid.

#include <cmath>
#include <vector>

#include "common/geometry.h"
#include "common/node/conversions.h"
#include "common/pose2.h"
#include "common/scan.h"
#include "minenav/ladar_scan_t.hpp"
#include "tests/log_contents.h"

namespace minenav::testing {

// A 20 x 20 m room centred on the origin, split by a partition at x = 4 whose 2 m door
// (y in [-1, 1]) is closed.
inline std::vector<Segment> DoorClosedRoom() {
  return {Segment(-10, -10, 10, -10), Segment(10, -10, 10, 10), Segment(10, 10, -10, 10), Segment(-10, 10, -10, -10),
          Segment(4, -10, 4, -1),     Segment(4, -1, 4, 1),     Segment(4, 1, 4, 10)};
}

// The same room with the door open (the door segment gone) and a 1 x 2 m box placed at
// x in [-6, -5], y in [-1, 1] (the vending machine of 4.8, free-standing here).
inline std::vector<Segment> DoorOpenRoomWithBox() {
  return {Segment(-10, -10, 10, -10), Segment(10, -10, 10, 10), Segment(10, 10, -10, 10), Segment(-10, 10, -10, -10),
          Segment(4, -10, 4, -1),     Segment(4, 1, 4, 10),     Segment(-6, -1, -5, -1),  Segment(-5, -1, -5, 1),
          Segment(-5, 1, -6, 1),      Segment(-6, 1, -6, -1)};
}

// Largest |range - CastRay(world)| over the valid readings of a scan taken at `pose`
// (sensor at the vehicle origin); infinity if a valid reading has no hit.
inline double MaxRangeError(const LadarScan& scan, const Pose2& pose, const std::vector<Segment>& world) {
  double worst = 0.0;
  for (size_t i = 0; i < scan.ranges.size(); ++i) {
    if (!scan.IsValid(i)) continue;
    const auto hit = CastRay(pose.translation(), pose.theta + scan.Bearing(i), world, 1e3);
    if (!hit) return INFINITY;
    worst = std::max(worst, std::abs(scan.ranges[i] - hit->range));
  }
  return worst;
}

struct WorldMatch {
  // Per scan: 0 = all ranges match world a within the tolerance, 1 = world b, -1 = neither.
  std::vector<int> world;
};

inline WorldMatch MatchScans(const std::vector<Logged<ladar_scan_t>>& scans, const Pose2& pose,
                             const std::vector<Segment>& a, const std::vector<Segment>& b, double tolerance) {
  WorldMatch m;
  for (const auto& s : scans) {
    const LadarScan scan = FromLcm(s.msg);
    if (MaxRangeError(scan, pose, a) <= tolerance)
      m.world.push_back(0);
    else if (MaxRangeError(scan, pose, b) <= tolerance)
      m.world.push_back(1);
    else
      m.world.push_back(-1);
  }
  return m;
}

// Indices where two scans' ranges differ by more than `tolerance`.
inline std::vector<size_t> DifferingReadings(const ladar_scan_t& p, const ladar_scan_t& q, double tolerance) {
  std::vector<size_t> out;
  for (size_t i = 0; i < p.ranges.size() && i < q.ranges.size(); ++i)
    if (std::abs(p.ranges[i] - q.ranges[i]) > tolerance) out.push_back(i);
  return out;
}

// Indices of the readings of `layout` (its bearings) at `pose` whose ray casts in a and b
// differ by more than `tolerance`: where the world changed, as the sensor sees it.
inline std::vector<size_t> DifferingRayCasts(const ladar_scan_t& layout, const Pose2& pose,
                                             const std::vector<Segment>& a, const std::vector<Segment>& b,
                                             double tolerance) {
  const LadarScan scan = FromLcm(layout);
  std::vector<size_t> out;
  for (size_t i = 0; i < scan.ranges.size(); ++i) {
    const double bearing = pose.theta + scan.Bearing(i);
    const auto ha = CastRay(pose.translation(), bearing, a, 1e3);
    const auto hb = CastRay(pose.translation(), bearing, b, 1e3);
    if (!ha || !hb || std::abs(ha->range - hb->range) > tolerance) out.push_back(i);
  }
  return out;
}

}  // namespace minenav::testing
