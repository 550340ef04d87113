#pragma once
// Messages in Foxglove's well-known schemas (docs.foxglove.dev, "Schemas"), JSON encoding,
// so Foxglove's and Lichtblick's 3D panel draws them: poses (foxglove.PoseInFrame), scans
// (foxglove.LaserScan: a planar scan's points at the sensor's pose) and maps as lines
// (foxglove.SceneUpdate with line strips). The map frame is "map"; z = 0, yaw as a
// quaternion about z. log_tool export-mcap writes them beside each channel's own JSON.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "minenav/ladar_scan_t.hpp"
#include "minenav/pose2d_t.hpp"

namespace minenav::foxglove_schemas {

inline constexpr const char* kPoseInFrame = "foxglove.PoseInFrame";
inline constexpr const char* kLaserScan = "foxglove.LaserScan";
inline constexpr const char* kSceneUpdate = "foxglove.SceneUpdate";
// The JSON Schema of each (the fields we write).
const std::string& SchemaText(const std::string& name);

struct Rgba {
  double r = 0, g = 0, b = 0, a = 1;
};

nlohmann::json PoseInFrame(int64_t utime, const std::string& frame, const pose2d_t& pose);
// The scan at the sensor's pose in `frame`: vehicle_pose composed with the scan's sensor offset.
nlohmann::json LaserScan(const ladar_scan_t& scan, const std::string& frame, const pose2d_t& vehicle_pose);
// One entity `id` whose polylines are line strips (closed ones repeat their first point).
struct Polyline {
  std::vector<Eigen::Vector2d> points;
  bool closed = false;
};
nlohmann::json SceneLines(int64_t utime, const std::string& frame, const std::string& id,
                          const std::vector<Polyline>& lines, const Rgba& color, double thickness_m);

// A message of minenav type `type_name` ("minenav.pose_estimate_t") in Foxglove's schema, when
// its type has one: {schema name, JSON}. Poses, true poses (frame map) and odometry (frame
// odometry) as PoseInFrame; scans as LaserScan at `scan_at` (frame map; nullopt: frame vehicle),
// every `scan_stride`-th reading; line maps and (inflated) contour maps as SceneUpdate line strips.
// Throws InputError when the payload does not decode.
std::optional<std::pair<std::string, nlohmann::json>> ToFoxglove(const std::string& channel, const std::string& type_name,
                                                                 const uint8_t* data, size_t size,
                                                                 const std::optional<pose2d_t>& scan_at,
                                                                 size_t scan_stride = 1);

}  // namespace minenav::foxglove_schemas
