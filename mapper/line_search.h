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

}  // namespace minenav::mapper
