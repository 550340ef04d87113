// Fuzz target: the segment-map JSON reader (common/file_io.h ParseSegmentsJson): worlds, the
// surveyed maps of the estimators, the planner's --map. What it accepts must survive its own
// writer: written (10 significant digits) and read back, the segments read back the same from
// then on.

#include <string>

#include "common/file_io.h"
#include "fuzz/finding.h"

namespace {

bool SegmentsEqual(const std::vector<minenav::Segment>& a, const std::vector<minenav::Segment>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].a != b[i].a || a[i].b != b[i].b) return false;
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string once;
  try {
    once = SegmentsToJson(ParseSegmentsJson(text, "fuzz"));
  } catch (const InputError&) {
    return 0;
  }
  const std::vector<Segment> read = ParseSegmentsJson(once, "written");
  if (!SegmentsEqual(read, ParseSegmentsJson(SegmentsToJson(read), "written again")))
    fuzz::Fail("segments written and read back change:\n" + once);
  return 0;
}
