#include "common/scan_split.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "common/angle.h"

namespace minenav {
namespace {

bool IsPresent(const Eigen::Vector2d& p) { return std::isfinite(p.x()) && std::isfinite(p.y()); }

// Whether present reading `to` continues the partial scan that present reading `from`
// ends; `to` comes after `from` in scan order, across the seam when to < from.
bool Linked(const ScanReadings& scan, int from, int to, const ScanSplitOptions& options) {
  const int total = static_cast<int>(scan.points.size());
  const int missing = (to > from ? to - from : to + total - from) - 1;
  if (missing > options.max_missing_readings) return false;
  const auto f = static_cast<size_t>(from), t = static_cast<size_t>(to);
  const double nearer = scan.ranges.empty() ? 0.0 : std::min(scan.ranges[f], scan.ranges[t]);
  return (scan.points[t] - scan.points[f]).norm() <= AllowedGap(nearer, scan.angle_step, options);
}

// The partial scans of a scan with two ends: a new one at every reading that does not link
// to the present reading before it.
std::vector<PartialScanReadings> SplitInScanOrder(const ScanReadings& scan, const ScanSplitOptions& options) {
  std::vector<PartialScanReadings> pieces;
  int previous = -1;
  for (int i = 0; i < static_cast<int>(scan.points.size()); ++i) {
    if (!IsPresent(scan.points[static_cast<size_t>(i)])) continue;
    if (previous < 0 || !Linked(scan, previous, i, options)) pieces.emplace_back();
    pieces.back().readings.push_back(i);
    previous = i;
  }
  return pieces;
}

bool MayWrapAround(const ScanReadings& scan, const ScanSplitOptions& options) {
  switch (options.wrap_around) {
    case WrapAround::kNever:
      return false;
    case WrapAround::kFullTurn:
      return CoversFullTurn(scan.points.size(), scan.angle_step);
    case WrapAround::kWhenEndsMeet:
      return true;
  }
  return false;
}

// When the scan's last present reading links to its first, the last partial scan continues
// into the first one; a single partial scan then closes on itself.
void JoinAcrossTheSeam(const ScanReadings& scan, const ScanSplitOptions& options,
                       std::vector<PartialScanReadings>* pieces) {
  if (pieces->empty() || !MayWrapAround(scan, options)) return;
  const int last = pieces->back().readings.back(), first = pieces->front().readings.front();
  if (last == first || !Linked(scan, last, first, options)) return;  // a lone reading has no seam
  if (pieces->size() == 1) {
    pieces->front().closed = true;
    return;
  }
  std::vector<int>& seam = pieces->back().readings;
  seam.insert(seam.end(), pieces->front().readings.begin(), pieces->front().readings.end());
  if (options.seam_partial_scan_first) {
    pieces->front() = std::move(pieces->back());
    pieces->pop_back();
  } else {
    pieces->erase(pieces->begin());
  }
}

}  // namespace

std::vector<PartialScanReadings> SplitScan(const ScanReadings& scan, const ScanSplitOptions& options) {
  std::vector<PartialScanReadings> pieces = SplitInScanOrder(scan, options);
  JoinAcrossTheSeam(scan, options, &pieces);
  std::erase_if(pieces, [&](const PartialScanReadings& piece) {
    return static_cast<int>(piece.readings.size()) < options.min_points;
  });
  return pieces;
}

double AllowedGap(double range, double angle_step, const ScanSplitOptions& options) {
  const double gap = options.break_distance + options.break_range_factor * range;
  const double step = std::abs(angle_step);
  if (options.break_incidence_angle <= step) return gap;
  return std::max(gap, range * std::sin(step) / std::sin(options.break_incidence_angle - step));
}

bool CoversFullTurn(size_t num_readings, double angle_step) {
  const double step = std::abs(angle_step);
  return step * static_cast<double>(num_readings) >= 2.0 * kPi - 1.5 * step;
}

}  // namespace minenav
