#include "viewer/foxglove_schemas.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "common/file_io.h"
#include "common/node/contour_map_conversions.h"
#include "common/node/conversions.h"
#include "minenav/contour_map_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "minenav/vehicle_truth_t.hpp"

namespace minenav::foxglove_schemas {

namespace {

using nlohmann::json;

json Time(int64_t utime) {
  const int64_t sec = utime >= 0 ? utime / 1'000'000 : 0;
  const int64_t nsec = utime >= 0 ? (utime % 1'000'000) * 1000 : 0;
  return {{"sec", sec}, {"nsec", nsec}};
}

json Pose(double x, double y, double theta) {
  return {{"position", {{"x", x}, {"y", y}, {"z", 0.0}}},
          {"orientation", {{"x", 0.0}, {"y", 0.0}, {"z", std::sin(theta / 2)}, {"w", std::cos(theta / 2)}}}};
}

// JSON Schemas of the fields we write (text: building them with nlohmann::json costs compile time).
#define MINENAV_TIME R"js({"type":"object","properties":{"sec":{"type":"integer","minimum":0},"nsec":{"type":"integer","minimum":0,"maximum":999999999}}})js"
#define MINENAV_VECTOR3 R"js({"type":"object","properties":{"x":{"type":"number"},"y":{"type":"number"},"z":{"type":"number"}}})js"
#define MINENAV_POSE R"js({"type":"object","properties":{"position":)js" MINENAV_VECTOR3 R"js(,"orientation":{"type":"object","properties":{"x":{"type":"number"},"y":{"type":"number"},"z":{"type":"number"},"w":{"type":"number"}}}}})js"
#define MINENAV_COLOR R"js({"type":"object","properties":{"r":{"type":"number"},"g":{"type":"number"},"b":{"type":"number"},"a":{"type":"number"}}})js"

constexpr const char* kPoseInFrameSchema =
    R"js({"title":"foxglove.PoseInFrame","type":"object","properties":{"timestamp":)js" MINENAV_TIME
    R"js(,"frame_id":{"type":"string"},"pose":)js" MINENAV_POSE R"js(}})js";
constexpr const char* kLaserScanSchema =
    R"js({"title":"foxglove.LaserScan","type":"object","properties":{"timestamp":)js" MINENAV_TIME
    R"js(,"frame_id":{"type":"string"},"pose":)js" MINENAV_POSE
    R"js(,"start_angle":{"type":"number"},"end_angle":{"type":"number"},"ranges":{"type":"array","items":{"type":["number","null"]}},"intensities":{"type":"array","items":{"type":"number"}}}})js";
constexpr const char* kSceneUpdateSchema =
    R"js({"title":"foxglove.SceneUpdate","type":"object","properties":{"deletions":{"type":"array"},"entities":{"type":"array","items":{"type":"object","properties":{"timestamp":)js" MINENAV_TIME
    R"js(,"frame_id":{"type":"string"},"id":{"type":"string"},"lifetime":{"type":"object"},"frame_locked":{"type":"boolean"},"metadata":{"type":"array"},"arrows":{"type":"array"},"cubes":{"type":"array"},"spheres":{"type":"array"},"cylinders":{"type":"array"},"lines":{"type":"array","items":{"type":"object","properties":{"type":{"type":"integer","description":"0 LINE_STRIP, 1 LINE_LOOP, 2 LINE_LIST"},"pose":)js" MINENAV_POSE
    R"js(,"thickness":{"type":"number"},"scale_invariant":{"type":"boolean"},"points":{"type":"array","items":)js" MINENAV_VECTOR3
    R"js(},"color":)js" MINENAV_COLOR R"js(,"colors":{"type":"array","items":)js" MINENAV_COLOR
    R"js(},"indices":{"type":"array","items":{"type":"integer"}}}}},"triangles":{"type":"array"},"texts":{"type":"array"},"models":{"type":"array"}}}}}})js";
#undef MINENAV_TIME
#undef MINENAV_VECTOR3
#undef MINENAV_POSE
#undef MINENAV_COLOR

}  // namespace

const std::string& SchemaText(const std::string& name) {
  static const std::map<std::string, std::string> schemas = {
      {kPoseInFrame, kPoseInFrameSchema}, {kLaserScan, kLaserScanSchema}, {kSceneUpdate, kSceneUpdateSchema}};
  static const std::string none;
  const auto it = schemas.find(name);
  return it == schemas.end() ? none : it->second;
}

json PoseInFrame(int64_t utime, const std::string& frame, const pose2d_t& pose) {
  return {{"timestamp", Time(utime)}, {"frame_id", frame}, {"pose", Pose(pose.x, pose.y, pose.theta)}};
}

json LaserScan(const ladar_scan_t& scan, const std::string& frame, const pose2d_t& v) {
  const pose2d_t& o = scan.sensor_offset;
  const double c = std::cos(v.theta), s = std::sin(v.theta);
  json ranges = json::array();
  for (const float r : scan.ranges) {
    const bool valid = std::isfinite(r) && r > 0.0f && r >= scan.min_range && r <= scan.max_range;
    ranges.push_back(valid ? json(r) : json(nullptr));
  }
  const double n = scan.ranges.empty() ? 0.0 : static_cast<double>(scan.ranges.size() - 1);
  return {{"timestamp", Time(scan.utime)},
          {"frame_id", frame},
          {"pose", Pose(v.x + c * o.x - s * o.y, v.y + s * o.x + c * o.y, v.theta + o.theta)},
          {"start_angle", scan.start_angle},
          {"end_angle", static_cast<double>(scan.start_angle) + n * static_cast<double>(scan.angle_step)},
          {"ranges", std::move(ranges)},
          {"intensities", scan.intensities}};
}

json SceneLines(int64_t utime, const std::string& frame, const std::string& id, const std::vector<Polyline>& lines,
                const Rgba& color, double thickness_m) {
  json strips = json::array();
  for (const Polyline& l : lines) {
    json points = json::array();
    for (const Eigen::Vector2d& p : l.points) points.push_back({{"x", p.x()}, {"y", p.y()}, {"z", 0.0}});
    strips.push_back({{"type", l.closed ? 1 : 0},
                      {"pose", Pose(0, 0, 0)},
                      {"thickness", thickness_m},
                      {"scale_invariant", false},
                      {"points", std::move(points)},
                      {"color", {{"r", color.r}, {"g", color.g}, {"b", color.b}, {"a", color.a}}},
                      {"colors", json::array()},
                      {"indices", json::array()}});
  }
  json entity = {{"timestamp", Time(utime)},
                 {"frame_id", frame},
                 {"id", id},
                 {"lifetime", {{"sec", 0}, {"nsec", 0}}},
                 {"frame_locked", false},
                 {"metadata", json::array()},
                 {"arrows", json::array()},
                 {"cubes", json::array()},
                 {"spheres", json::array()},
                 {"cylinders", json::array()},
                 {"lines", std::move(strips)},
                 {"triangles", json::array()},
                 {"texts", json::array()},
                 {"models", json::array()}};
  return {{"deletions", json::array()}, {"entities", json::array({std::move(entity)})}};
}

namespace {

template <typename T>
T Decode(const std::string& channel, const uint8_t* data, size_t size) {
  T m{};
  std::string error;
  if (!DecodeMessage(data, static_cast<int>(size), channel, &m, &error)) throw InputError(error);
  return m;
}

}  // namespace

std::optional<std::pair<std::string, json>> ToFoxglove(const std::string& channel, const std::string& type,
                                                       const uint8_t* data, size_t size,
                                                       const std::optional<pose2d_t>& scan_at, size_t scan_stride) {
  if (type == "minenav.pose_estimate_t") {
    const auto m = Decode<pose_estimate_t>(channel, data, size);
    return std::pair{std::string(kPoseInFrame), PoseInFrame(m.utime, "map", m.pose)};
  }
  if (type == "minenav.vehicle_truth_t") {
    const auto m = Decode<vehicle_truth_t>(channel, data, size);
    return std::pair{std::string(kPoseInFrame), PoseInFrame(m.utime, "map", m.pose)};
  }
  if (type == "minenav.odometry_t") {
    const auto m = Decode<odometry_t>(channel, data, size);
    return std::pair{std::string(kPoseInFrame), PoseInFrame(m.utime, "odometry", m.pose)};
  }
  if (type == "minenav.ladar_scan_t") {
    ladar_scan_t m = Decode<ladar_scan_t>(channel, data, size);
    const size_t stride = std::max<size_t>(1, scan_stride);
    if (stride > 1) {
      std::vector<float> kept;
      for (size_t i = 0; i < m.ranges.size(); i += stride) kept.push_back(m.ranges[i]);
      m.ranges = std::move(kept);
      m.num_ranges = static_cast<int32_t>(m.ranges.size());
      m.intensities.clear();
      m.num_intensities = 0;
      m.angle_step = static_cast<float>(static_cast<double>(m.angle_step) * static_cast<double>(stride));
    }
    return std::pair{std::string(kLaserScan), LaserScan(m, scan_at ? "map" : "vehicle", scan_at.value_or(pose2d_t{}))};
  }
  if (type == "minenav.line_map_t") {
    const auto m = Decode<line_map_t>(channel, data, size);
    std::vector<Polyline> lines;
    for (const line_segment_t& s : m.segments) lines.push_back({{{s.x1, s.y1}, {s.x2, s.y2}}, false});
    return std::pair{std::string(kSceneUpdate), SceneLines(m.utime, "map", channel, lines, {0.5, 0.5, 0.5, 1.0}, 0.05)};
  }
  if (type == "minenav.contour_map_t") {
    const ContourMapMessage map = ContourMapFromLcm(Decode<contour_map_t>(channel, data, size));
    std::vector<Polyline> lines;
    for (const ContourPolyline& c : map.contours) lines.push_back({c.points, c.closed});
    return std::pair{std::string(kSceneUpdate),
                     SceneLines(map.utime, "map", channel, lines, {0.12, 0.37, 0.75, 1.0}, 0.08)};
  }
  return std::nullopt;
}

}  // namespace minenav::foxglove_schemas
