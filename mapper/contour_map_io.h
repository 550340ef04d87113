#pragma once
// The contour-map file contract (DESIGN.md "File contracts"):
//   {"contours": [{"closed": false, "points": [[x, y], ...]}, ...]}
// metres, world frame; points ordered with the sensed free space on the left (contour.h),
// i.e. counter-clockwise as seen from the free space. Other keys are allowed and ignored
// (an optional integer "id" per contour is written and read back when present). Readers
// validate everything and throw InputError with one line naming the source, the contour
// and what is wrong; writers write atomically (common/file_io.h).

#include <string>

#include "mapper/contour_map.h"

namespace minenav::mapper {

ContourMap ParseContourMapJson(const std::string& text, const std::string& source_name,
                               double grid_cell_size = 2.0);
ContourMap LoadContourMapJson(const std::string& path, double grid_cell_size = 2.0);
std::string ContourMapToJson(const ContourMap& map);
void SaveContourMapJson(const std::string& path, const ContourMap& map);

}  // namespace minenav::mapper
