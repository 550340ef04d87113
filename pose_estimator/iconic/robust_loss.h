#pragma once
// Robust losses for the Gauss-Newton minimisation, applied as iteratively reweighted least
// squares. Beyond the thesis (3.1.2 footnote: uncertainty modelling was never done): they
// keep clutter that is not in the map and mixed pixels from pulling the estimate.

#include <cmath>
#include <string>

namespace minenav {

enum class RobustLoss { kNone, kHuber, kCauchy };

inline const char* ToString(RobustLoss loss) {
  switch (loss) {
    case RobustLoss::kNone: return "none";
    case RobustLoss::kHuber: return "huber";
    case RobustLoss::kCauchy: return "cauchy";
  }
  return "?";
}

inline bool ParseRobustLoss(const std::string& text, RobustLoss* out) {
  if (text == "none") *out = RobustLoss::kNone;
  else if (text == "huber") *out = RobustLoss::kHuber;
  else if (text == "cauchy") *out = RobustLoss::kCauchy;
  else return false;
  return true;
}

// IRLS weight rho'(f) / f for a residual f (m) and scale k (m).
inline double RobustWeight(RobustLoss loss, double f, double k) {
  const double a = std::abs(f);
  switch (loss) {
    case RobustLoss::kNone: return 1.0;
    case RobustLoss::kHuber: return a <= k ? 1.0 : k / a;
    case RobustLoss::kCauchy: return 1.0 / (1.0 + (f / k) * (f / k));
  }
  return 1.0;
}

}  // namespace minenav
