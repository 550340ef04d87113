// Fuzz target: the contour-map JSON reader (mapper/contour_map_io.h ParseContourMapJson): the
// mapper's --load-map, the planner's --contour-map, the log tools. What it accepts must survive
// its own writer (fuzz/round_trip.h; it writes 9 significant digits): the same contours, ids
// and points (-0 and 0 are one coordinate).

#include <string>

#include "fuzz/round_trip.h"
#include "mapper/contour_map_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  using mapper::ContourMap;
  fuzz::CheckWrittenReadsBack(
      data, size, "contour map JSON",
      [](const std::string& text, const std::string& source) { return mapper::ParseContourMapJson(text, source); },
      mapper::ContourMapToJson, [](const ContourMap& a, const ContourMap& b) {
        if (a.contours().size() != b.contours().size()) return false;
        for (auto i = a.contours().begin(), k = b.contours().begin(); i != a.contours().end(); ++i, ++k) {
          if (i->first != k->first || i->second.closed != k->second.closed || i->second.points != k->second.points)
            return false;
        }
        return true;
      });
  return 0;
}
