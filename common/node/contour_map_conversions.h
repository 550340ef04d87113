#pragma once
// contour_map_t <-> plain contours (lcmtypes/contour_map_t.lcm): small maps travel plain,
// maps whose plain encoding exceeds a size travel zlib-compressed in `payload` (UDP loses a
// whole message when one fragment is lost, and the default socket buffers drop messages
// over about 64 KB: DESIGN.md "The bus"). Readers inflate and validate, throwing InputError
// with one line.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "minenav/contour_map_t.hpp"

namespace minenav {

struct ContourPolyline {
  int64_t id = -1;
  bool closed = false;
  std::vector<Eigen::Vector2d> points;  // m, map frame (sent as float)
};

struct ContourMapMessage {
  int64_t utime = 0;
  int64_t version = 0;
  int32_t num_scans = 0;
  std::vector<ContourPolyline> contours;
};

// Default threshold for compression (bytes of the plain encoding).
inline constexpr int kContourMapCompressAbove = 32 * 1024;

// Largest plain encoding a compressed CONTOUR_MAP may inflate to (bytes). A 1 km² mine
// mapped at 0.5 m segments is a few MB.
inline constexpr int64_t kMaxUncompressedContourMap = 64 << 20;

// Plain when the plain encoding is at most compress_above bytes, else compressed.
contour_map_t ContourMapToLcm(const ContourMapMessage& map, int compress_above = kContourMapCompressAbove);
// Either encoding; validates sizes, finiteness and the compressed payload.
ContourMapMessage ContourMapFromLcm(const contour_map_t& m);

}  // namespace minenav
