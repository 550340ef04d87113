// Fuzz target: the contour mapper's checkpoint (mapper/map_checkpoint.h) read as the process
// reads it at start-up: OpenMappingSession with --checkpoint FILE (LoadCheckpoint: the magic,
// sizes, hash and every value checked; then RestoreSession: the map, its grid and the scans
// rebuilt), with the process's options (the survey preset).

#include "common/file_io.h"
#include "common/log.h"
#include "fuzz/scratch_file.h"
#include "fuzz/mapper_process_options.h"
#include "mapper/contour_mapper_node.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  SetLogLevel(LogLevel::kError);
  static const ContourMapperNodeOptions defaults = fuzz::MapperProcessDefaults();
  const fuzz::ScratchFile file(data, size);
  ContourMapperNodeOptions options = defaults;
  options.checkpoint = file.path();
  try {
    (void)OpenMappingSession(options);
  } catch (const InputError&) {
  }
  return 0;
}
