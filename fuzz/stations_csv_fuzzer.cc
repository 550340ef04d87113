// Fuzz target: the scan stations CSV reader (common/file_io.h ParseStationsCsv: survey_client,
// the log tools). What it accepts must survive its own writer.

#include <string>

#include "common/file_io.h"
#include "fuzz/finding.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string once;
  try {
    once = StationsToCsv(ParseStationsCsv(text, "fuzz"));
  } catch (const InputError&) {
    return 0;
  }
  if (StationsToCsv(ParseStationsCsv(once, "round trip")) != once)
    fuzz::Fail("stations CSV round trip changes the stations");
  return 0;
}
