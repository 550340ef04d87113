#pragma once
// Scan preprocessing for the contour mapper (thesis 4.2, 7.2.3): trim to a range interval,
// median filter, segmentation into partial scans at discontinuities (fixed, or adaptive to
// range for sparse scanners), and optional density reduction.
//
// Orientation: every partial scan lists its points in order of increasing bearing as seen
// from the sensor (counter-clockwise around the sensor), whatever the sign of the scan's
// angle_step. Walking a partial scan in that order, the sensor (free space) lies on the
// LEFT. Contours inherit this convention (contour.h).

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/scan.h"

namespace minenav::mapper {

struct ScanPreprocessingOptions {
  // m; readings below this are discarded (0 = the scan's own min_range).
  double min_range = 0.0;
  // m; readings above this are discarded (0 = the scan's own max_range).
  double max_range = 0.0;
  // Readings; odd, 1 disables the median filter (thesis: useful for Cyclone, off for Typhoon).
  int median_filter_size = 1;
  // m; consecutive points farther apart than this start a new partial scan.
  double discontinuity_threshold = 0.5;
  // rad; range-adaptive discontinuity (adaptive breakpoint detector, Borges & Aldon 2004):
  // the gap allowed after a reading at range r is raised to r·sin Δφ / sin(λ − Δφ), the gap a
  // wall seen at incidence λ to the beam leaves between readings Δφ apart. Sparse scans
  // (1° SICK readings at 10–40 m) otherwise break far walls into pieces too short to keep,
  // while a fixed threshold large enough for them would join near objects. 0 = off (the
  // fixed threshold alone, as in the thesis); must exceed the angle step when on.
  double discontinuity_angle = 0.0;
  // Points; partial scans with fewer points are dropped (isolated mixed pixels, clutter).
  int min_points_per_partial_scan = 4;
  // Drop mixed pixels (common/mixed_pixels.h): one or two readings between two surfaces at an
  // occlusion, off the continuation of each, judged by the scan's own range noise
  // (common/range_noise.h). Left
  // in, one between a post and a wall up to twice discontinuity_threshold behind it joins the
  // two along the ray, and the map gets a contour there (the research mine's worst deviation).
  bool drop_mixed_pixels = true;
  // rad; only from scans whose angular step is at most this (the mining ladars' 0.18 deg): at
  // a SICK's 0.5-1 deg a surface one or two readings wide is an object (a chair leg, a door
  // frame) and an oblique wall is not straight in range over four readings (Intel's relation
  // error went from 0.019 to 0.22 m with the rule on).
  double mixed_pixel_max_step = 0.005;
  // m; density reduction (7.2.3): within a partial scan keep a point only when it is at
  // least this far from the last kept point (the last point is always kept). 0 = off.
  double min_point_spacing = 0.0;
};

// Returns an empty string when the options are usable, else a one-line reason.
std::string ValidateOptions(const ScanPreprocessingOptions& options);
// Declares every field of `o` under `scope` (unit, default, range, why): config keys and flags.
void DeclareOptions(OptionScope scope, ScanPreprocessingOptions& o);

// A sequential run of scan points with no discontinuity, in the vehicle frame.
struct PartialScan {
  std::vector<Eigen::Vector2d> points;  // m, vehicle frame, counter-clockwise about the sensor
  int first_index = 0;  // index of the first point's reading in the original scan
  int last_index = 0;   // index of the last point's reading
};

// A scan ready for the mapper: partial scans in the vehicle frame.
struct PreprocessedScan {
  int64_t utime = 0;
  Eigen::Vector2d sensor_position = Eigen::Vector2d::Zero();  // m, vehicle frame
  std::vector<PartialScan> partial_scans;

  int NumPoints() const;
};

// Median of the valid ranges in a window of `size` readings centred on each valid reading
// (invalid readings are left invalid and are not used). size 1 returns the input.
std::vector<float> MedianFilterRanges(const std::vector<float>& ranges, const std::vector<bool>& valid,
                                      int size);

// Whole pipeline. Partial scans are split by common/scan_split.h: invalid readings (NaN,
// out of the range interval) break them; on a full 360° scan the partial scans that meet
// across the seam are merged.
PreprocessedScan PreprocessScan(const LadarScan& scan, const ScanPreprocessingOptions& options);

// The largest gap between consecutive points that does not start a new partial scan, after
// a reading at `range` m with readings `angle_step` rad apart (see discontinuity_angle).
double DiscontinuityGap(double range, double angle_step, const ScanPreprocessingOptions& options);

// Density reduction on one polyline (keeps first and last point).
std::vector<Eigen::Vector2d> ReduceDensity(const std::vector<Eigen::Vector2d>& points, double min_spacing);

}  // namespace minenav::mapper
