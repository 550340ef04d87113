#pragma once
// The one-dimensional search of thesis 4.3.3 / 4.5.2: along a descent direction, find a
// step λ in (0, λ_max] that lowers the error. λ is in the units of the caller's
// direction (the mapper normalises directions so that λ is a distance in metres or an
// angle in radians). First the step is halved from λ_max until the error stops falling
// (a binary search, as in the thesis), then a golden-section search refines the best
// bracket down to the resolution.

#include <functional>

namespace minenav::mapper {

struct LineSearchResult {
  double lambda = 0.0;  // 0: no step lowered the error
  double value = 0.0;   // error at lambda
  int evaluations = 0;
};

LineSearchResult LineSearch(const std::function<double(double)>& error, double error_at_zero,
                            double lambda_max, double resolution);

// For an error that is exactly quadratic along the line (the integral error under a pure
// translation of the scan, correspondence fixed): the minimum from the value and slope at 0
// and the value at λ_max, clamped to (0, λ_max]. Two evaluations instead of tens; falls back
// to LineSearch if the quadratic model does not lower the error (e.g. not convex).
LineSearchResult QuadraticLineSearch(const std::function<double(double)>& error, double error_at_zero,
                                     double slope_at_zero, double lambda_max, double resolution);

}  // namespace minenav::mapper
