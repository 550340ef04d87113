#include "mapper/line_search.h"

#include <algorithm>
#include <cmath>

namespace minenav::mapper {

LineSearchResult LineSearch(const std::function<double(double)>& error, double error_at_zero,
                            double lambda_max, double resolution) {
  LineSearchResult best{0.0, error_at_zero, 0};
  if (!(lambda_max > 0.0) || !(resolution > 0.0)) return best;
  for (double l = lambda_max; l >= resolution; l *= 0.5) {
    const double v = error(l);
    ++best.evaluations;
    if (v < best.value) {
      best.lambda = l;
      best.value = v;
    } else if (best.lambda > 0.0) {
      break;  // the error rose again on the way down: the minimum is bracketed
    }
  }
  if (best.lambda <= 0.0) return best;
  // Golden section on [λ/2, min(2λ, λ_max)], keeping the best point seen.
  double a = 0.5 * best.lambda, b = std::min(2.0 * best.lambda, lambda_max);
  constexpr double kInvPhi = 0.6180339887498949;
  double c = b - kInvPhi * (b - a), d = a + kInvPhi * (b - a);
  double fc = error(c), fd = error(d);
  best.evaluations += 2;
  for (int k = 0; k < 40 && b - a > resolution; ++k) {
    if (fc < fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - kInvPhi * (b - a);
      fc = error(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + kInvPhi * (b - a);
      fd = error(d);
    }
    ++best.evaluations;
  }
  if (fc < best.value) best = {c, fc, best.evaluations};
  if (fd < best.value) best = {d, fd, best.evaluations};
  return best;
}

LineSearchResult QuadraticLineSearch(const std::function<double(double)>& error, double error_at_zero,
                                     double slope_at_zero, double lambda_max, double resolution) {
  LineSearchResult best{0.0, error_at_zero, 0};
  if (!(lambda_max > 0.0) || !(slope_at_zero < 0.0)) return best;
  const double f_max = error(lambda_max);
  best.evaluations = 1;
  if (f_max < best.value) best = {lambda_max, f_max, 1};
  const double a = (f_max - error_at_zero - slope_at_zero * lambda_max) / (lambda_max * lambda_max);
  if (a > 0.0) {
    const double l = std::min(lambda_max, -slope_at_zero / (2.0 * a));
    if (l >= resolution && l < lambda_max) {
      const double v = error(l);
      ++best.evaluations;
      if (v < best.value) best = {l, v, best.evaluations};
    }
  }
  if (best.lambda > 0.0) return best;
  LineSearchResult fallback = LineSearch(error, error_at_zero, lambda_max, resolution);
  fallback.evaluations += best.evaluations;
  return fallback;
}

}  // namespace minenav::mapper
