#include "pose_estimator/iconic/iconic_test_world.h"

#include <cmath>
#include <limits>

#include "common/angle.h"

namespace minenav::testing {

std::vector<Segment> RoomWorld() {
  return {
      // Outer walls, with an alcove cut into the top-right corner.
      {0, 0, 20, 0}, {20, 0, 20, 8}, {20, 8, 16, 8}, {16, 8, 16, 12}, {16, 12, 0, 12}, {0, 12, 0, 0},
      // A pillar, off centre.
      {6, 4, 8, 4}, {8, 4, 8, 6}, {8, 6, 6, 6}, {6, 6, 6, 4},
      // A short slanted wall piece.
      {12, 2, 14, 3.5},
  };
}

LadarScan ExactScan(const std::vector<Segment>& world, const Pose2& pose, int n, double sigma, uint32_t seed,
                    int64_t utime) {
  LadarScan scan;
  scan.utime = utime;
  scan.sensor_id = "test";
  scan.start_angle = -kPi;
  scan.angle_step = 2.0 * kPi / n;
  scan.min_range = 0.1;
  scan.max_range = 50.0;
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  for (int i = 0; i < n; ++i) {
    const double bearing = pose.theta + scan.Bearing(static_cast<size_t>(i));
    const auto hit = CastRay(pose.translation(), bearing, world, scan.max_range);
    double r = hit ? hit->range : std::numeric_limits<double>::quiet_NaN();
    if (hit && sigma > 0.0) r += noise(rng);
    scan.ranges.push_back(static_cast<float>(r));
  }
  return scan;
}

}  // namespace minenav::testing
