// Fuzz target: the scan stations CSV reader (common/file_io.h ParseStationsCsv: survey_client,
// the log tools). What it accepts must survive its own writer (fuzz/round_trip.h).

#include "common/file_io.h"
#include "fuzz/round_trip.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  fuzz::CheckWrittenReadsBack(data, size, "stations CSV", ParseStationsCsv, StationsToCsv,
                              [](const auto& a, const auto& b) { return StationsToCsv(a) == StationsToCsv(b); });
  return 0;
}
