#pragma once
// Angle helpers. All angles in radians.

#include <cmath>
#include <numbers>

namespace minenav {

inline constexpr double kPi = std::numbers::pi;

// Wraps an angle to (-pi, pi].
inline double NormalizeAngle(double a) {
  a = std::remainder(a, 2.0 * kPi);  // [-pi, pi]
  return a <= -kPi ? a + 2.0 * kPi : a;
}

inline constexpr double DegToRad(double deg) { return deg * kPi / 180.0; }
inline constexpr double RadToDeg(double rad) { return rad * 180.0 / kPi; }

}  // namespace minenav
