#pragma once
// The one way the fleet splits a scan into partial scans at range discontinuities
// (occlusions, thesis 3.3; preprocessing, 4.2; breaking into pieces, 2.1.4). Walking the
// readings in scan order, two neighbouring readings stay in one partial scan when few enough
// readings are missing between them and their points are no farther apart than the gap
// allowed at their range; a scan that covers a full turn may continue from its last
// readings into its first ones. The iconic estimator's polylines (scan_polylines.h), the
// contour mapper's preprocessing (scan_preprocessing.h) and the feature extractor's pieces
// (feature_extraction.cc) all split here, each mapping its own options onto these.

#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <span>
#include <vector>

namespace minenav {

// For ScanSplitOptions::max_missing_readings: neighbours may be any number of readings apart.
inline constexpr int kAnyNumberOfMissingReadings = std::numeric_limits<int>::max();

// Whether the last readings of a scan may continue into its first ones.
enum class WrapAround {
  kNever,         // the scan has two ends
  kFullTurn,      // when the readings cover a full turn (CoversFullTurn)
  kWhenEndsMeet,  // whenever the last reading links to the first: for points that carry no
                  // bearing, where only the caller knows the scan is a full turn
};

struct ScanSplitOptions {
  // m; the gap allowed between neighbouring points is never below this. Default 0.5 m:
  // well above twice the range noise of a mining ladar (thesis 3.3), below the gaps that
  // occlusions leave.
  double break_distance = 0.5;
  // 1; the allowed gap grows by this fraction of the nearer reading's range: a wall seen at
  // a grazing angle has its readings spread in proportion to range. Default 0 (a fixed gap).
  double break_range_factor = 0.0;
  // rad; range-adaptive gap (adaptive breakpoint detector, Borges & Aldon 2004): the gap
  // allowed after a reading at range r is raised to r·sin Δφ / sin(λ − Δφ), the gap a wall
  // seen at incidence λ to the beam leaves between readings Δφ apart. Sparse scans (1°
  // readings at 10-40 m) otherwise break far walls into pieces too short to keep. Default
  // 0 = off; also off while λ <= Δφ, where the formula has no meaning.
  double break_incidence_angle = 0.0;
  // readings; neighbours may have at most this many missing readings between them.
  // Default 0: nothing says the surface continues through a reading the ladar did not
  // return. kAnyNumberOfMissingReadings ignores missing readings altogether.
  int max_missing_readings = 0;
  // Default kFullTurn: a 360° scanner's seam lies between two neighbouring readings like
  // any other pair, so a wall across it stays one partial scan.
  WrapAround wrap_around = WrapAround::kFullTurn;
  // Where the partial scan that crosses the seam is listed: first (it holds the scan's first
  // reading) or last (every partial scan listed at its first reading in scan order). Only
  // the order changes. Default true, as the iconic estimator and the mapper list them.
  bool seam_partial_scan_first = true;
  // points; partial scans with fewer readings are dropped (mixed pixels, clutter). Default
  // 3, the fewest that show which way a surface bends.
  int min_points = 3;
};

// One scan's readings in scan order, as the splitter sees them (a view: the caller owns
// the data).
struct ScanReadings {
  std::span<const Eigen::Vector2d> points;  // m, any frame, one per reading; non-finite = missing
  // m, one per reading; read only at present readings. Empty: every reading counts as
  // range 0, so only break_distance applies.
  std::span<const double> ranges;
  double angle_step = 0.0;  // rad between readings (sign ignored); 0 = unknown
};

// A partial scan: the readings it holds, in walking order.
struct PartialScanReadings {
  // Indices of its readings into the scan, increasing, except that a partial scan across
  // the seam runs on from the scan's last readings into its first ones.
  std::vector<int> readings;
  // A full turn without a single break, the seam included: the last reading links back to
  // the first.
  bool closed = false;
};

// Splits a scan into partial scans, listed in scan order (see seam_partial_scan_first).
std::vector<PartialScanReadings> SplitScan(const ScanReadings& scan, const ScanSplitOptions& options);

// The largest gap between neighbouring points that does not break a partial scan, at the
// nearer reading's `range` m, with readings `angle_step` rad apart: break_distance plus
// break_range_factor·range, raised to the adaptive gap when that is on and larger.
double AllowedGap(double range, double angle_step, const ScanSplitOptions& options);

// Whether `num_readings` readings `angle_step` rad apart go all the way round: they cover
// at least 2π less 1.5 steps, so rounding in angle_step never decides it and a scanner that
// leaves out the reading at the seam still counts.
bool CoversFullTurn(size_t num_readings, double angle_step);

}  // namespace minenav
