// Fuzz target: the CARMEN log reader (dataset_readers/carmen_log.h ReadCarmenLog): plain text,
// gzip or bzip2 recognised by the first bytes, decompressed and parsed as a stream (the line
// limit is what stops a decompression bomb).

#include "common/file_io.h"
#include "dataset_readers/carmen_log.h"
#include "fuzz/scratch_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  const fuzz::ScratchFile file(data, size);
  try {
    (void)ReadCarmenLog(file.path());
  } catch (const InputError&) {
  }
  return 0;
}
