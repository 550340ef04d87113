// Fuzz target: the segment-map JSON reader (common/file_io.h ParseSegmentsJson): worlds, the
// surveyed maps of the estimators, the planner's --map. What it accepts must survive its own
// writer (fuzz/round_trip.h; it writes 10 significant digits): the same segments.

#include <vector>

#include "common/file_io.h"
#include "fuzz/round_trip.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  fuzz::CheckWrittenReadsBack(data, size, "segments JSON", ParseSegmentsJson, SegmentsToJson,
                              [](const std::vector<Segment>& a, const std::vector<Segment>& b) {
                                if (a.size() != b.size()) return false;
                                for (size_t i = 0; i < a.size(); ++i)
                                  if (a[i].a != b[i].a || a[i].b != b[i].b) return false;
                                return true;
                              });
  return 0;
}
