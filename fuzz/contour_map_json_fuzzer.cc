// Fuzz target: the contour-map JSON reader (mapper/contour_map_io.h ParseContourMapJson): the
// mapper's --load-map, the planner's --contour-map, the log tools. What it accepts must survive
// its own writer (ContourMapToJson -> ParseContourMapJson: the same contours).

#include <string>

#include "common/file_io.h"
#include "fuzz/finding.h"
#include "mapper/contour_map_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string once;
  try {
    once = mapper::ContourMapToJson(mapper::ParseContourMapJson(text, "fuzz"));
  } catch (const InputError&) {
    return 0;
  }
  const std::string twice = mapper::ContourMapToJson(mapper::ParseContourMapJson(once, "round trip"));
  if (twice != once) fuzz::Fail("contour map JSON round trip changes the map");
  return 0;
}
