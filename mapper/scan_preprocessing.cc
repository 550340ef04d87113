#include "mapper/scan_preprocessing.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "common/angle.h"
#include "common/mixed_pixels.h"
#include "common/range_noise.h"
#include "common/scan_split.h"

namespace minenav::mapper {

std::string ValidateOptions(const ScanPreprocessingOptions& o) {
  std::ostringstream why;
  if (!(o.min_range >= 0.0) || !(o.max_range >= 0.0))
    why << "min_range/max_range must be >= 0 (0 = the scan's own limit)";
  else if (o.max_range > 0.0 && o.min_range >= o.max_range)
    why << "min_range " << o.min_range << " m must be below max_range " << o.max_range << " m";
  else if (o.median_filter_size < 1 || o.median_filter_size % 2 == 0)
    why << "median_filter_size must be odd and >= 1, got " << o.median_filter_size;
  else if (!(o.discontinuity_threshold > 0.0))
    why << "discontinuity_threshold must be > 0 m, got " << o.discontinuity_threshold;
  else if (!(o.discontinuity_angle >= 0.0 && o.discontinuity_angle < kPi / 2.0))
    why << "discontinuity_angle must be in [0, pi/2) rad, got " << o.discontinuity_angle;
  else if (o.min_points_per_partial_scan < 2)
    why << "min_points_per_partial_scan must be >= 2, got " << o.min_points_per_partial_scan;
  else if (!(o.mixed_pixel_max_step >= 0.0))
    why << "mixed_pixel_max_step must be >= 0 rad, got " << o.mixed_pixel_max_step;
  else if (!(o.min_point_spacing >= 0.0))
    why << "min_point_spacing must be >= 0 m, got " << o.min_point_spacing;
  return why.str();
}

void DeclareOptions(OptionScope s, ScanPreprocessingOptions& o) {
  s.AddDouble("min_range", &o.min_range, "m",
              "readings below this are discarded; 0 = the scan's own min_range (the limit the sensor reports)",
              0.0, 1000.0);
  s.AddDouble("max_range", &o.max_range, "m",
              "readings above this are discarded; 0 = the scan's own max_range (far readings through "
              "doors and windows carry most mixed pixels: sparse scans want a limit, CARMEN 40 m)",
              0.0, 1000.0);
  s.AddInt("median_filter_size", &o.median_filter_size,
           "odd number of readings in the range median filter (4.2); 1 = off: the thesis found it useful for "
           "the Cyclone, not for the Typhoon [readings]",
           1, 101);
  s.AddDouble("discontinuity_threshold", &o.discontinuity_threshold, "m",
              "consecutive points farther apart start a new partial scan; 0.5 m is wider than the spacing of a "
              "dense scan's points along a wall",
              0.001, 100.0);
  s.AddDouble("discontinuity_angle", &o.discontinuity_angle, "rad",
              "range-adaptive break (adaptive breakpoint detector): after a reading at range r the gap may reach "
              "r sin(dphi) / sin(this - dphi), the gap of a wall seen at this incidence; 0 = the fixed "
              "threshold alone (thesis); sparse 1-degree scans want 10 degrees, else far walls fall apart",
              0.0, 1.57);
  s.AddInt("min_points_per_partial_scan", &o.min_points_per_partial_scan,
           "partial scans with fewer points are dropped (isolated mixed pixels, clutter); 4 keeps "
           "short real walls and drops single stray returns [points]",
           2, 1000000);
  s.AddBool("drop_mixed_pixels", &o.drop_mixed_pixels,
            "drop one or two readings between two surfaces at an occlusion, off the continuation of each "
            "(mixed pixels, judged by the range noise measured from the scan): left in, one joins a post to a "
            "wall up to twice discontinuity_threshold behind it, along the ray (true)");
  s.AddDouble("mixed_pixel_max_step", &o.mixed_pixel_max_step, "rad",
              "drop mixed pixels only from scans whose angular step is at most this: at a SICK's 0.5-1 deg a "
              "surface one or two readings wide is an object and an oblique wall is not straight in range over "
              "four readings (0.005 rad: the mining ladars' 0.18 deg pass)",
              0.0, 1.0);
  s.AddDouble("min_point_spacing", &o.min_point_spacing, "m",
              "density reduction (7.2.3): within a partial scan keep a point only this far from the last kept "
              "one; 0 = off, every point is kept",
              0.0, 10.0);
}

int PreprocessedScan::NumPoints() const {
  int n = 0;
  for (const PartialScan& p : partial_scans) n += static_cast<int>(p.points.size());
  return n;
}

std::vector<float> MedianFilterRanges(const std::vector<float>& ranges, const std::vector<bool>& valid,
                                      int size) {
  if (size <= 1) return ranges;
  const int n = static_cast<int>(ranges.size());
  const int half = size / 2;
  std::vector<float> out = ranges;
  std::vector<float> window;
  window.reserve(static_cast<size_t>(size));
  for (int i = 0; i < n; ++i) {
    if (!valid[static_cast<size_t>(i)]) continue;
    window.clear();
    for (int k = std::max(0, i - half); k <= std::min(n - 1, i + half); ++k)
      if (valid[static_cast<size_t>(k)]) window.push_back(ranges[static_cast<size_t>(k)]);
    const auto mid = window.begin() + static_cast<std::ptrdiff_t>(window.size() / 2);
    std::nth_element(window.begin(), mid, window.end());
    out[static_cast<size_t>(i)] = *mid;
  }
  return out;
}

namespace {
// The preprocessing options as the one splitter's (common/scan_split.h). The rest are the
// splitter's defaults, which are the mapper's rules: an invalid reading (NaN, out of the
// range interval) breaks a partial scan, and on a full 360° scan the partial scans that
// meet across the seam are one, listed first.
ScanSplitOptions PartialScanSplitOptions(const ScanPreprocessingOptions& options) {
  ScanSplitOptions split;
  split.break_distance = options.discontinuity_threshold;
  split.break_incidence_angle = options.discontinuity_angle;
  split.min_points = options.min_points_per_partial_scan;
  return split;
}
}  // namespace

double DiscontinuityGap(double range, double angle_step, const ScanPreprocessingOptions& options) {
  return AllowedGap(range, angle_step, PartialScanSplitOptions(options));
}

std::vector<Eigen::Vector2d> ReduceDensity(const std::vector<Eigen::Vector2d>& points, double min_spacing) {
  if (min_spacing <= 0.0 || points.size() <= 2) return points;
  std::vector<Eigen::Vector2d> out;
  out.push_back(points.front());
  for (size_t i = 1; i + 1 < points.size(); ++i)
    if ((points[i] - out.back()).norm() >= min_spacing) out.push_back(points[i]);
  // The last point always stays; drop the previous kept one if it crowds it.
  if (out.size() > 1 && (points.back() - out.back()).norm() < 0.5 * min_spacing) out.pop_back();
  out.push_back(points.back());
  return out;
}

PreprocessedScan PreprocessScan(const LadarScan& scan, const ScanPreprocessingOptions& options) {
  PreprocessedScan out;
  out.utime = scan.utime;
  out.sensor_position = scan.sensor_offset.translation();
  const size_t n = scan.ranges.size();
  if (n == 0) return out;

  const double lo = std::max(scan.min_range, options.min_range);
  const double hi = options.max_range > 0.0 ? std::min(scan.max_range, options.max_range) : scan.max_range;
  std::vector<bool> valid(n);
  for (size_t i = 0; i < n; ++i) {
    const float r = scan.ranges[i];
    valid[i] = std::isfinite(r) && r > 0.0f && r >= lo && r <= hi;
  }
  const std::vector<float> ranges = MedianFilterRanges(scan.ranges, valid, options.median_filter_size);
  if (options.drop_mixed_pixels && std::abs(scan.angle_step) <= options.mixed_pixel_max_step) {
    const double noise = std::max(MeasureRangeNoise(scan).sigma, kLeastUsefulRangeNoise);
    const std::vector<bool> mixed = FindMixedPixels(ranges, valid, noise);
    for (size_t i = 0; i < n; ++i)
      if (mixed[i]) valid[i] = false;
  }

  // Points in the vehicle frame, in reading order; invalid readings stay NaN (missing).
  std::vector<Eigen::Vector2d> pts(n, Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN()));
  for (size_t i = 0; i < n; ++i) {
    if (!valid[i]) continue;
    const double r = ranges[i], a = scan.Bearing(i);
    pts[i] = scan.sensor_offset * Eigen::Vector2d(r * std::cos(a), r * std::sin(a));
  }
  // The gap allowed grows with the nearer reading's (filtered) range: a far point after a
  // near one is an occlusion, not the same wall.
  const std::vector<double> split_ranges(ranges.begin(), ranges.end());
  const ScanReadings readings{.points = pts, .ranges = split_ranges, .angle_step = scan.angle_step};
  for (const PartialScanReadings& run : SplitScan(readings, PartialScanSplitOptions(options))) {
    PartialScan partial;
    partial.first_index = run.readings.front();
    partial.last_index = run.readings.back();
    partial.points.reserve(run.readings.size());
    for (const int i : run.readings) partial.points.push_back(pts[static_cast<size_t>(i)]);
    if (scan.angle_step < 0.0) {  // keep counter-clockwise order about the sensor
      std::reverse(partial.points.begin(), partial.points.end());
      std::swap(partial.first_index, partial.last_index);
    }
    partial.points = ReduceDensity(partial.points, options.min_point_spacing);
    out.partial_scans.push_back(std::move(partial));
  }
  return out;
}

}  // namespace minenav::mapper
