#pragma once
// A planar ladar scan as algorithms see it: no LCM, same fields as minenav::ladar_scan_t.
// Reading i was taken at bearing start_angle + i * angle_step in the sensor frame; the
// sensor frame sits at sensor_offset in the vehicle frame.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "common/pose2.h"

namespace minenav {

struct LadarScan {
  int64_t utime = 0;       // us, time of the first reading
  int64_t scan_id = 0;
  std::string sensor_id;
  Pose2 sensor_offset;     // sensor pose in the vehicle frame
  double start_angle = 0.0;      // rad
  double angle_step = 0.0;       // rad
  double min_range = 0.0;        // m
  double max_range = 0.0;        // m
  double range_resolution = 0.0; // m, 0 = not quantised
  double scan_duration = 0.0;    // s
  std::vector<float> ranges;     // m; invalid readings are NaN, <= 0 or outside [min, max]
  std::vector<float> intensities;  // empty or one per range

  double Bearing(size_t i) const { return start_angle + static_cast<double>(i) * angle_step; }
  bool IsValid(size_t i) const;
};

// One valid reading turned into a point.
struct ScanPoint {
  Eigen::Vector2d point;  // m, in the frame asked for
  double range = 0.0;     // m
  double bearing = 0.0;   // rad, sensor frame
  int index = 0;          // index of the reading in the scan
};

// Valid readings as points in the sensor frame.
std::vector<ScanPoint> ScanPointsInSensorFrame(const LadarScan& scan);
// Valid readings as points in the vehicle frame (through sensor_offset).
std::vector<ScanPoint> ScanPointsInVehicleFrame(const LadarScan& scan);
// Valid readings in the world frame for a vehicle at world_T_vehicle.
std::vector<Eigen::Vector2d> ScanPointsInWorld(const LadarScan& scan, const Pose2& world_T_vehicle);

// Checks the scan's own consistency (finite angles, min < max, intensities sized like
// ranges). Returns an empty string when fine, else a one-line reason.
std::string ValidateScan(const LadarScan& scan);

}  // namespace minenav
