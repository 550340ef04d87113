#pragma once
// The contour-map file contract (DESIGN.md "File contracts"):
//   {"contours": [{"closed": false, "points": [[x, y], ...]}, ...]}
// metres, world frame; points ordered with the sensed free space on the left (contour.h),
// i.e. counter-clockwise as seen from the free space. Other keys are allowed and ignored
// (an optional integer "id" per contour is written and read back when present). Readers
// validate everything and throw InputError with one line naming the source, the contour
// and what is wrong; writers write atomically (common/file_io.h).
//
// Geometry that no survey makes is refused as corrupt (issue 11, item 7: a 66-byte map with
// one 20 km segment made the segment grid allocate 6 GB): a vertex farther than
// kMaxMapCoordinate from the origin, or a segment longer than kMaxSegmentLength. The mapper
// makes 0.5 m segments; a hand-drawn map may draw a long straight rib as one segment, but
// not one longer than a kilometre. Checkpoints (map_checkpoint.h) apply the same limits.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mapper/contour_map.h"

namespace minenav::mapper {

// m; largest |x| or |y| of a contour vertex (10 000 km: UTM coordinates fit, garbage not).
inline constexpr double kMaxMapCoordinate = 1e7;
// m; longest contour segment (the closing segment of a closed contour included).
inline constexpr double kMaxSegmentLength = 1000.0;

// "" when the contour's vertices are finite and within both limits, else one line naming
// the first offending point or segment (without the source; callers prefix it).
std::string CheckContourGeometry(const std::vector<Eigen::Vector2d>& points, bool closed);

ContourMap ParseContourMapJson(const std::string& text, const std::string& source_name,
                               double grid_cell_size = 2.0);
ContourMap LoadContourMapJson(const std::string& path, double grid_cell_size = 2.0);
std::string ContourMapToJson(const ContourMap& map);
void SaveContourMapJson(const std::string& path, const ContourMap& map);

}  // namespace minenav::mapper
