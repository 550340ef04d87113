// Fuzz target: the poses CSV reader (common/file_io.h ParsePosesCsv: --poses-out files read back
// by the log tools and the relations metric). What it accepts must survive its own writer.

#include <string>

#include "common/file_io.h"
#include "fuzz/finding.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string once;
  try {
    once = PosesToCsv(ParsePosesCsv(text, "fuzz"));
  } catch (const InputError&) {
    return 0;
  }
  if (PosesToCsv(ParsePosesCsv(once, "round trip")) != once) fuzz::Fail("poses CSV round trip changes the poses");
  return 0;
}
