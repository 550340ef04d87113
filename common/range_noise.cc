#include "common/range_noise.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace minenav {

namespace {

double Cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

}  // namespace

RangeNoise MeasureRangeNoise(const LadarScan& scan) {
  RangeNoise out;
  // A ray within this angle of its neighbours' line meets it too far from the points to say
  // anything about the noise (sin 5 deg).
  const double kMinSine = 0.087;
  std::vector<double> off;
  off.reserve(scan.ranges.size());
  for (size_t i = 1; i + 1 < scan.ranges.size(); ++i) {
    if (!scan.IsValid(i - 1) || !scan.IsValid(i) || !scan.IsValid(i + 1)) continue;
    const double b0 = scan.Bearing(i - 1), b1 = scan.Bearing(i), b2 = scan.Bearing(i + 1);
    const double r0 = scan.ranges[i - 1], r2 = scan.ranges[i + 1];
    const double ax = r0 * std::cos(b0), ay = r0 * std::sin(b0);
    const double dx = r2 * std::cos(b2) - ax, dy = r2 * std::sin(b2) - ay;
    const double ux = std::cos(b1), uy = std::sin(b1);
    const double length = std::hypot(dx, dy);
    const double across = Cross(ux, uy, dx, dy);  // length * sin(angle between ray and line)
    if (!(length > 0.0) || std::abs(across) < kMinSine * length) continue;
    const double on_line = Cross(ax, ay, dx, dy) / across;  // range where ray i meets the line
    const double d = std::abs(static_cast<double>(scan.ranges[i]) - on_line);
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
