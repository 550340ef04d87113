// Fuzz target: the poses CSV reader (common/file_io.h ParsePosesCsv: --poses-out files read back
// by the log tools and the relations metric). What it accepts must survive its own writer
// (fuzz/round_trip.h).

#include "common/file_io.h"
#include "fuzz/round_trip.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  fuzz::CheckWrittenReadsBack(data, size, "poses CSV", ParsePosesCsv, PosesToCsv,
                              [](const auto& a, const auto& b) { return PosesToCsv(a) == PosesToCsv(b); });
  return 0;
}
