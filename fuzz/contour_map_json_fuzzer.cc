// Fuzz target: the contour-map JSON reader (mapper/contour_map_io.h ParseContourMapJson): the
// mapper's --load-map, the planner's --contour-map, the log tools. What it accepts must survive
// its own writer: written (9 significant digits) and read back, the map reads back the same
// from then on (the same contours, ids and points; -0 and 0 are one coordinate).

#include <string>

#include "common/file_io.h"
#include "fuzz/finding.h"
#include "mapper/contour_map_io.h"

namespace {

bool SameMap(const minenav::mapper::ContourMap& a, const minenav::mapper::ContourMap& b) {
  if (a.contours().size() != b.contours().size()) return false;
  for (auto i = a.contours().begin(), k = b.contours().begin(); i != a.contours().end(); ++i, ++k) {
    if (i->first != k->first || i->second.closed != k->second.closed || i->second.points != k->second.points)
      return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string once;
  try {
    once = mapper::ContourMapToJson(mapper::ParseContourMapJson(text, "fuzz"));
  } catch (const InputError&) {
    return 0;
  }
  const mapper::ContourMap read = mapper::ParseContourMapJson(once, "written");
  const mapper::ContourMap again = mapper::ParseContourMapJson(mapper::ContourMapToJson(read), "written again");
  if (!SameMap(read, again)) fuzz::Fail("a contour map written and read back changes:\n" + once);
  return 0;
}
