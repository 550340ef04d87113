#pragma once
// Whether the tests run under AddressSanitizer, and how much slower that makes them: timing
// assertions are requirements of the normal build, scaled by kSlowdown under ASan/UBSan.

namespace minenav::testing {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kUnderAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kUnderAddressSanitizer = true;
#else
inline constexpr bool kUnderAddressSanitizer = false;
#endif
#else
inline constexpr bool kUnderAddressSanitizer = false;
#endif

// ASan/UBSan builds run 2-3x slower (more on a loaded machine); small fixed-size Eigen
// arithmetic far more: the contour fit's integral error 19x under ASan (tracker/cutter_bus_test.cc).
inline constexpr double kSlowdown = kUnderAddressSanitizer ? 3.0 : 1.0;

}  // namespace minenav::testing
