#include "common/node/conversions.h"

#include <cmath>

#include "common/file_io.h"
#include "common/segment_index.h"

namespace minenav {

namespace {

// Beyond these a value is absurd, and refused like a non-finite one: finite but huge numbers
// overflow the arithmetic downstream (fuzz.contour_mapper.small: an ODOMETRY pose at y = 9e170
// made the mapper publish a contour map with non-finite points). A coordinate is absurd where
// the segment index stops listing it (StaticSegmentIndex::kMaxCoordinate, 1e12 m); unwrapped
// headings accumulate turns, 1e6 rad is 160,000 of them; no vehicle moves at 1 km/s.
constexpr double kMaxAbsCoordinate = StaticSegmentIndex::kMaxCoordinate;  // m
constexpr double kMaxAbsHeading = 1e6;                                    // rad
constexpr double kMaxAbsRate = 1e3;         // m/s and rad/s

void CheckFinite(double v, const char* field, const char* type) {
  if (!std::isfinite(v)) throw InputError(std::string(type) + "." + field + " is not finite");
}

void CheckRate(double v, const char* field, const char* type) {
  CheckFinite(v, field, type);
  if (std::abs(v) > kMaxAbsRate) throw InputError(std::string(type) + "." + field + " is absurd (beyond 1e3)");
}

void CheckPose(const pose2d_t& p, const char* field, const char* type) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.theta))
    throw InputError(std::string(type) + "." + field + " is not finite");
  if (std::abs(p.x) > kMaxAbsCoordinate || std::abs(p.y) > kMaxAbsCoordinate || std::abs(p.theta) > kMaxAbsHeading)
    throw InputError(std::string(type) + "." + field + " is absurd (beyond 1e12 m or 1e6 rad)");
}

Eigen::Matrix3d CovarianceFrom(const double (&c)[9]) {
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) m(r, k) = c[3 * r + k];
  return m;
}

void CovarianceTo(const Eigen::Matrix3d& m, double (&c)[9]) {
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) c[3 * r + k] = m(r, k);
}

}  // namespace

pose2d_t ToLcm(const Pose2& p) {
  pose2d_t m{};
  m.x = p.x;
  m.y = p.y;
  m.theta = p.theta;
  return m;
}

Pose2 FromLcm(const pose2d_t& m) {
  CheckPose(m, "pose", "pose2d_t");
  return {m.x, m.y, NormalizeAngle(m.theta)};
}

ladar_scan_t ToLcm(const LadarScan& s) {
  ladar_scan_t m{};
  m.utime = s.utime;
  m.scan_id = s.scan_id;
  m.sensor_id = s.sensor_id;
  m.sensor_offset = ToLcm(s.sensor_offset);
  m.start_angle = static_cast<float>(s.start_angle);
  m.angle_step = static_cast<float>(s.angle_step);
  m.min_range = static_cast<float>(s.min_range);
  m.max_range = static_cast<float>(s.max_range);
  m.range_resolution = static_cast<float>(s.range_resolution);
  m.scan_duration = static_cast<float>(s.scan_duration);
  m.num_ranges = static_cast<int32_t>(s.ranges.size());
  m.ranges = s.ranges;
  m.num_intensities = static_cast<int32_t>(s.intensities.size());
  m.intensities = s.intensities;
  return m;
}

LadarScan FromLcm(const ladar_scan_t& m) {
  if (m.num_ranges < 0 || static_cast<size_t>(m.num_ranges) != m.ranges.size())
    throw InputError("ladar_scan_t.num_ranges does not match ranges");
  if (m.num_intensities < 0 || static_cast<size_t>(m.num_intensities) != m.intensities.size())
    throw InputError("ladar_scan_t.num_intensities does not match intensities");
  CheckPose(m.sensor_offset, "sensor_offset", "ladar_scan_t");
  LadarScan s;
  s.utime = m.utime;
  s.scan_id = m.scan_id;
  s.sensor_id = m.sensor_id;
  s.sensor_offset = FromLcm(m.sensor_offset);
  s.start_angle = m.start_angle;
  s.angle_step = m.angle_step;
  s.min_range = m.min_range;
  s.max_range = m.max_range;
  s.range_resolution = m.range_resolution;
  s.scan_duration = m.scan_duration;
  s.ranges = m.ranges;
  s.intensities = m.intensities;
  const std::string why = ValidateScan(s);
  if (!why.empty()) throw InputError("ladar_scan_t: " + why);
  return s;
}

odometry_t ToLcm(const OdometryReading& o) {
  odometry_t m{};
  m.utime = o.utime;
  m.seq = o.seq;
  m.pose = ToLcm(o.pose);
  m.v = o.v;
  m.omega = o.omega;
  CovarianceTo(o.covariance, m.covariance);
  return m;
}

OdometryReading FromLcm(const odometry_t& m) {
  CheckPose(m.pose, "pose", "odometry_t");
  CheckRate(m.v, "v", "odometry_t");
  CheckRate(m.omega, "omega", "odometry_t");
  OdometryReading o;
  o.utime = m.utime;
  o.seq = m.seq;
  o.pose = FromLcm(m.pose);
  o.v = m.v;
  o.omega = m.omega;
  o.covariance = CovarianceFrom(m.covariance);
  return o;
}

vehicle_truth_t ToLcm(const TruthReading& t) {
  vehicle_truth_t m{};
  m.utime = t.utime;
  m.seq = t.seq;
  m.pose = ToLcm(t.pose);
  m.v = t.v;
  m.omega = t.omega;
  return m;
}

TruthReading FromLcm(const vehicle_truth_t& m) {
  CheckPose(m.pose, "pose", "vehicle_truth_t");
  return {m.utime, m.seq, FromLcm(m.pose), m.v, m.omega};
}

drive_command_t ToLcm(const DriveCommand& c) {
  drive_command_t m{};
  m.utime = c.utime;
  m.seq = c.seq;
  m.mode = static_cast<int8_t>(c.mode);
  m.v = c.v;
  m.omega = c.omega;
  m.timeout = c.timeout;
  return m;
}

DriveCommand FromLcm(const drive_command_t& m) {
  if (m.mode < drive_command_t::STOP || m.mode > drive_command_t::TURN_IN_PLACE)
    throw InputError("drive_command_t.mode " + std::to_string(m.mode) + " is unknown");
  CheckRate(m.v, "v", "drive_command_t");
  CheckRate(m.omega, "omega", "drive_command_t");
  if (!std::isfinite(m.timeout) || m.timeout < 0) throw InputError("drive_command_t.timeout must be >= 0");
  DriveCommand c;
  c.utime = m.utime;
  c.seq = m.seq;
  c.mode = static_cast<DriveCommand::Mode>(m.mode);
  c.v = m.v;
  c.omega = m.omega;
  c.timeout = m.timeout;
  return c;
}

pose_estimate_t ToLcm(const PoseEstimate& e) {
  pose_estimate_t m{};
  m.utime = e.utime;
  m.scan_id = e.scan_id;
  m.source = e.source;
  m.pose = ToLcm(e.pose);
  CovarianceTo(e.covariance, m.covariance);
  m.residual = e.residual;
  m.num_points = e.num_points;
  m.num_inliers = e.num_inliers;
  m.iterations = e.iterations;
  m.converged = e.converged;
  m.status = e.status;
  m.compute_time = static_cast<float>(e.compute_time);
  return m;
}

PoseEstimate FromLcm(const pose_estimate_t& m) {
  CheckPose(m.pose, "pose", "pose_estimate_t");
  PoseEstimate e;
  e.utime = m.utime;
  e.scan_id = m.scan_id;
  e.source = m.source;
  e.pose = FromLcm(m.pose);
  e.covariance = CovarianceFrom(m.covariance);
  e.residual = m.residual;
  e.num_points = m.num_points;
  e.num_inliers = m.num_inliers;
  e.iterations = m.iterations;
  e.converged = m.converged;
  e.status = m.status;
  e.compute_time = m.compute_time;
  return e;
}

line_map_t SegmentsToLcm(const std::vector<Segment>& segments, int64_t utime, int64_t version,
                         const std::string& name) {
  line_map_t m{};
  m.utime = utime;
  m.version = version;
  m.name = name;
  m.num_segments = static_cast<int32_t>(segments.size());
  m.segments.reserve(segments.size());
  for (const Segment& s : segments) {
    line_segment_t l{};
    l.x1 = s.a.x();
    l.y1 = s.a.y();
    l.x2 = s.b.x();
    l.y2 = s.b.y();
    m.segments.push_back(l);
  }
  return m;
}

std::vector<Segment> SegmentsFromLcm(const line_map_t& m) {
  if (m.num_segments < 0 || static_cast<size_t>(m.num_segments) != m.segments.size())
    throw InputError("line_map_t.num_segments does not match segments");
  std::vector<Segment> out;
  out.reserve(m.segments.size());
  for (size_t i = 0; i < m.segments.size(); ++i) {
    const auto& l = m.segments[i];
    if (!std::isfinite(l.x1) || !std::isfinite(l.y1) || !std::isfinite(l.x2) || !std::isfinite(l.y2))
      throw InputError("line_map_t.segments[" + std::to_string(i) + "] is not finite");
    out.emplace_back(l.x1, l.y1, l.x2, l.y2);
  }
  return out;
}

}  // namespace minenav
