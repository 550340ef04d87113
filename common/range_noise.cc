#include "common/range_noise.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace minenav {

RangeNoise MeasureRangeNoise(const LadarScan& scan) {
  RangeNoise out;
  // A ray within this angle of its neighbours' line meets it too far from the points to say
  // anything about the noise (sin 5 deg).
  const double kMinSine = 0.087;
  const std::vector<ScanPoint> points = ScanPointsInSensorFrame(scan);  // each reading's trig once
  std::vector<double> off;
  off.reserve(points.size());
  for (size_t k = 1; k + 1 < points.size(); ++k) {
    const ScanPoint &before = points[k - 1], &at = points[k], &after = points[k + 1];
    if (before.index + 1 != at.index || at.index + 1 != after.index) continue;  // three consecutive readings
    const Eigen::Vector2d along = after.point - before.point;
    const Eigen::Vector2d ray = at.point / at.range;  // a valid reading's range is > 0
    const double length = along.norm();
    const double across = ray.x() * along.y() - ray.y() * along.x();  // length * sin(ray, line)
    if (!(length > 0.0) || std::abs(across) < kMinSine * length) continue;
    // The range where ray k meets the line through its neighbours' points.
    const double on_line = (before.point.x() * along.y() - before.point.y() * along.x()) / across;
    const double d = std::abs(at.range - on_line);
    if (std::isfinite(d)) off.push_back(d);  // (bearings from a hostile angle_step may be NaN)
  }
  out.triples = static_cast<int>(off.size());
  if (out.triples < kMinRangeNoiseTriples) return out;
  // A first, robust scale from the median; then the RMS of the differences within three of
  // it (quantised ranges make the differences take a few discrete values, whose median lies
  // on one of them: up to 20 % off, where an RMS averages over them).
  const double kMadToSigma = 1.4826, kVariance = std::sqrt(1.5);
  const auto middle = off.begin() + static_cast<std::ptrdiff_t>(off.size() / 2);
  std::nth_element(off.begin(), middle, off.end());
  const double quantum_sigma = scan.range_resolution > 0.0 ? scan.range_resolution / std::sqrt(12.0) : 0.0;
  const double gate = 3.0 * std::max(kMadToSigma * *middle, quantum_sigma * kVariance);
  double sum = 0.0;
  int n = 0;
  for (const double d : off)
    if (d <= gate) sum += d * d, ++n;
  // A Gaussian cut at 3 sigma keeps 97.3 % of its variance.
  const double kTruncatedVariance = 0.9733;
  out.sigma = n > 0 ? std::sqrt(sum / n / kTruncatedVariance) / kVariance : 0.0;
  out.sigma = std::max(out.sigma, quantum_sigma);
  return out;
}

}  // namespace minenav
