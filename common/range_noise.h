#pragma once
// The range noise of a ladar, measured from one scan's own readings: what a user would
// otherwise have to know and type (the Typhoon's 4.4 cm, the Cyclone's 10 cm, a SICK's
// 1 cm) to every estimator that weighs or gates points by it.
//
// For every three consecutive valid readings, the middle reading's range is compared with
// where its ray meets the line through its two neighbours' points. On a flat wall the true
// points are collinear, so the difference is the noise alone, at any incidence and any
// angular step (the second difference of the ranges themselves is not: r'' dphi^2 reaches
// centimetres on an oblique wall at a SICK's 1 degree). With independent range noise of
// standard deviation sigma the difference is about n[i] - (n[i-1] + n[i+1]) / 2, of
// variance 1.5 sigma^2. A median first (1.4826 median(|d|) / sqrt(1.5): the median absolute
// value of Gaussian noise is 0.6745 sigma), which ignores the minority of triples that
// straddle a corner, an occlusion or a mixed pixel; then the RMS of the differences within
// three of that, which quantised ranges need (their differences take a few discrete values,
// and a median lands on one of them). Quantisation (range_resolution q) adds q^2 / 12 as
// any noise does; the estimate is never below q / sqrt(12).

#include "common/scan.h"

namespace minenav {

struct RangeNoise {
  double sigma = 0.0;  // m; 0 when there were fewer than kMinRangeNoiseTriples triples
  int triples = 0;     // triples of consecutive valid readings the estimate used
};

// m; the least range noise worth judging points by: below it the walls' roughness and the
// map's survey, not the sensor, decide how well a point fits (the FPE's range_noise_floor, the
// mapper's mixed-pixel test).
inline constexpr double kLeastUsefulRangeNoise = 0.01;

// Fewer triples than this give no estimate (sigma 0): the median of fewer would wander.
inline constexpr int kMinRangeNoiseTriples = 50;

// The scan's range noise (standard deviation, m) from every three consecutive valid
// readings (a ray that grazes its neighbours' line, within 5 degrees, is left out).
RangeNoise MeasureRangeNoise(const LadarScan& scan);

}  // namespace minenav
