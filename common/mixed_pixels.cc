#include "common/mixed_pixels.h"

#include <algorithm>
#include <cmath>

namespace minenav {

std::vector<bool> FindMixedPixels(const std::vector<float>& ranges, const std::vector<bool>& valid,
                                  double range_noise, const MixedPixelOptions& options) {
  const int n = static_cast<int>(std::min(ranges.size(), valid.size()));
  std::vector<bool> mixed(static_cast<size_t>(n), false);
  const double t = options.noise_factor * range_noise;
  if (!(t > 0.0)) return mixed;
  const auto r = [&](int i) { return static_cast<double>(ranges[static_cast<size_t>(i)]); };
  const auto ok = [&](int i) { return i >= 0 && i < n && valid[static_cast<size_t>(i)]; };
  // A surface beside the run: the kSurface readings that end at `edge` (going away from the
  // run by `away` = -1 or +1), all valid; its range extrapolated to reading `at` by the
  // straight line through its two ends (a wall at any incidence is nearly straight in range
  // over a few readings).
  constexpr int kSurface = 4;
  const auto surface = [&](int edge, int away) {
    for (int k = 0; k < kSurface; ++k)
      if (!ok(edge + away * k)) return false;
    // Straight: the inner readings within t of the line through the ends (no jump inside).
    const double first = r(edge), last = r(edge + away * (kSurface - 1));
    for (int k = 1; k + 1 < kSurface; ++k)
      if (std::abs(r(edge + away * k) - (first + (last - first) * k / (kSurface - 1))) > t) return false;
    return true;
  };
  const auto extrapolate = [&](int edge, int away, int at) {
    const double slope = (r(edge) - r(edge + away * (kSurface - 1))) / (kSurface - 1);  // per reading toward the run
    return r(edge) + slope * std::abs(at - edge);
  };
  for (int a = kSurface; a + kSurface < n; ++a) {
    if (!ok(a) || !surface(a - 1, -1)) continue;
    // The longest run first: two mixed readings are not one and a surface.
    for (int len = options.max_run; len >= 1; --len) {
      const int b = a + len - 1;  // the run is [a, b]; the far surface starts at b + 1
      if (!ok(b) || !surface(b + 1, +1)) continue;
      // Each reading of the run lies between both surfaces as they continue, off each by t and
      // by the noise of the extrapolation (about a sigma a reading).
      bool mixed_run = true;
      for (int i = a; i <= b && mixed_run; ++i) {
        const double off_near = r(i) - extrapolate(a - 1, -1, i), off_far = r(i) - extrapolate(b + 1, +1, i);
        mixed_run = off_near * off_far < 0.0 && std::abs(off_near) > t + range_noise * (i - a + 1) &&
                    std::abs(off_far) > t + range_noise * (b + 1 - i);
      }
      if (!mixed_run) continue;
      for (int i = a; i <= b; ++i) mixed[static_cast<size_t>(i)] = true;
      break;
    }
  }
  return mixed;
}

}  // namespace minenav
