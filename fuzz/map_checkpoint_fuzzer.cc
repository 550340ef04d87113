// Fuzz target: the contour mapper's checkpoint (mapper/map_checkpoint.h) read as the process
// reads it at start-up: OpenMappingSession with --checkpoint FILE (LoadCheckpoint: the magic,
// sizes, hash and every value checked; then RestoreSession: the map, its grid and the scans
// rebuilt), with the process's options (the survey preset).
//
// An input that starts with the magic number is the file as it is. Any other input is a
// payload, framed here as a checkpoint is framed (magic, version 1, size, payload, FNV-1a of
// the payload: map_checkpoint.cc): mutations of the payload then reach the value checks and
// RestoreSession instead of stopping at the hash.

#include <cstring>
#include <string>

#include "common/file_io.h"
#include "common/log.h"
#include "fuzz/mapper_process_options.h"
#include "fuzz/scratch_file.h"
#include "mapper/contour_mapper_node.h"

namespace {

constexpr char kMagic[8] = {'M', 'N', 'C', 'L', 'U', 'E', 'C', 'K'};

template <typename T>
void Append(std::string* out, T v) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &v, sizeof(T));
  out->append(bytes, sizeof(T));
}

std::string Framed(const std::string& payload) {
  uint64_t hash = 1469598103934665603ull;
  for (const char c : payload) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ull;
  }
  std::string file(kMagic, sizeof(kMagic));
  Append<uint32_t>(&file, 1);
  Append<uint64_t>(&file, payload.size());
  file += payload;
  Append<uint64_t>(&file, hash);
  return file;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  SetLogLevel(LogLevel::kError);
  static const ContourMapperNodeOptions defaults = fuzz::MapperProcessDefaults();
  std::string bytes(reinterpret_cast<const char*>(data), size);
  if (bytes.compare(0, sizeof(kMagic), kMagic, sizeof(kMagic)) != 0) bytes = Framed(bytes);
  const fuzz::ScratchFile file(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  ContourMapperNodeOptions options = defaults;
  options.checkpoint = file.path();
  try {
    (void)OpenMappingSession(options);
  } catch (const InputError&) {
  }
  return 0;
}
