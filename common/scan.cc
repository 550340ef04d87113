#include "common/scan.h"

#include <cmath>
#include <sstream>

namespace minenav {

bool LadarScan::IsValid(size_t i) const {
  const float r = ranges[i];
  return std::isfinite(r) && r > 0.0f && r >= min_range && r <= max_range;
}

std::vector<ScanPoint> ScanPointsInSensorFrame(const LadarScan& scan) {
  std::vector<ScanPoint> out;
  out.reserve(scan.ranges.size());
  for (size_t i = 0; i < scan.ranges.size(); ++i) {
    if (!scan.IsValid(i)) continue;
    const double r = scan.ranges[i];
    const double a = scan.Bearing(i);
    out.push_back({Eigen::Vector2d(r * std::cos(a), r * std::sin(a)), r, a, static_cast<int>(i)});
  }
  return out;
}

std::vector<ScanPoint> ScanPointsInVehicleFrame(const LadarScan& scan) {
  std::vector<ScanPoint> out = ScanPointsInSensorFrame(scan);
  for (ScanPoint& p : out) p.point = scan.sensor_offset * p.point;
  return out;
}

std::vector<Eigen::Vector2d> ScanPointsInWorld(const LadarScan& scan, const Pose2& world_T_vehicle) {
  const Pose2 world_T_sensor = world_T_vehicle * scan.sensor_offset;
  std::vector<Eigen::Vector2d> out;
  out.reserve(scan.ranges.size());
  for (const ScanPoint& p : ScanPointsInSensorFrame(scan)) out.push_back(world_T_sensor * p.point);
  return out;
}

std::string ValidateScan(const LadarScan& scan) {
  std::ostringstream why;
  if (!std::isfinite(scan.start_angle) || !std::isfinite(scan.angle_step))
    why << "start_angle/angle_step not finite";
  else if (scan.ranges.size() > 1 && scan.angle_step == 0.0)
    why << "angle_step is 0 with " << scan.ranges.size() << " readings";
  else if (!(scan.min_range >= 0.0) || !(scan.max_range > scan.min_range))
    why << "range limits [" << scan.min_range << ", " << scan.max_range << "] are not 0 <= min < max";
  else if (!scan.intensities.empty() && scan.intensities.size() != scan.ranges.size())
    why << scan.intensities.size() << " intensities for " << scan.ranges.size() << " ranges";
  else if (!std::isfinite(scan.sensor_offset.x) || !std::isfinite(scan.sensor_offset.y) ||
           !std::isfinite(scan.sensor_offset.theta))
    why << "sensor_offset not finite";
  else if (std::abs(scan.angle_step) * static_cast<double>(scan.ranges.size()) > 2.0 * kPi + 1e-6)
    why << "scan covers more than 360 degrees";
  return why.str();
}

}  // namespace minenav
