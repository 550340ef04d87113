// Fuzz target: the LCM event log reader (common/node/event_log.h LogReader, the one parser of
// logs: batch mode, the log tools, the ladar's replay): every event read in place until the end
// or the first damage (an InputError naming the byte offset).

#include "common/file_io.h"
#include "common/node/event_log.h"
#include "fuzz/scratch_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  const fuzz::ScratchFile file(data, size);
  try {
    LogReader reader(file.path());
    while (reader.NextInPlace() != nullptr) {
    }
  } catch (const InputError&) {
  }
  return 0;
}
