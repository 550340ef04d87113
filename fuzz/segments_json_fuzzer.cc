// Fuzz target: the segment-map JSON reader (common/file_io.h ParseSegmentsJson): worlds, the
// surveyed maps of the estimators, the planner's --map. What it accepts must survive its own
// writer: SegmentsToJson -> ParseSegmentsJson gives the same segments.

#include <string>

#include "common/file_io.h"
#include "fuzz/finding.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<Segment> segments;
  try {
    segments = ParseSegmentsJson(text, "fuzz");
  } catch (const InputError&) {
    return 0;
  }
  const std::vector<Segment> again = ParseSegmentsJson(SegmentsToJson(segments), "round trip");
  if (again.size() != segments.size()) fuzz::Fail("segments JSON round trip changes the count");
  for (size_t i = 0; i < again.size(); ++i)
    if (!(again[i].a == segments[i].a) || !(again[i].b == segments[i].b))
      fuzz::Fail("segments JSON round trip changes segment " + std::to_string(i));
  return 0;
}
