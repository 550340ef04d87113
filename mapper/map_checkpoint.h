#pragma once
// Checkpoints of a mapping run (issue 5: "checkpoints its whole state ... so that a restart
// resumes with nothing lost"): every inserted scan with its partial scans (vehicle frame),
// pose and fixed flag; every contour with its id and the map's next id; the session's
// odometry anchor, counters and pose rows. Thesis 4.1.2: the scans are kept because contour
// fitting and concurrent refinement (4.5, 4.7) re-use all of them.
//
// Format (little-endian, doubles as their IEEE bits so a round trip is bit-exact):
//   8 bytes magic "MNCLUECK", u32 version (1), u64 payload size, payload, u64 FNV-1a hash
//   of the payload. Loading validates the magic, version, sizes, hash and every value
//   (finite numbers, contour sizes, unique ids below next_id, indices in range; contour
//   geometry within contour_map_io.h's limits, positions within kMaxMapCoordinate, scan
//   points within 1 km of their vehicle: what no survey makes is refused) and throws
//   InputError with one line naming the file and what is wrong. Saving is atomic and durable
//   (WriteFileAtomically: temp file, fsync, rename, fsync of the folder), and the checkpoint
//   it replaces stays as FILE.prev: a crash mid-write leaves the previous checkpoint, and a
//   checkpoint found torn or corrupt all the same (a power cut on a disk that lied about
//   its flush, a copy cut short) is replaced by FILE.prev at the restart (issue 16, "a torn
//   checkpoint ... is detected and the last good one used").

#include <string>
#include <vector>

#include "mapper/mapping_session.h"

namespace minenav::mapper {

struct MapperCheckpoint {
  std::vector<Contour> contours;  // ids kept
  int next_contour_id = 0;
  std::vector<MappedScan> scans;
  MappingSessionState session;
};

MapperCheckpoint CheckpointOf(const MappingSession& session);
std::string EncodeCheckpoint(const MapperCheckpoint& checkpoint);
// Throws InputError naming `source_name`.
MapperCheckpoint DecodeCheckpoint(const std::string& bytes, const std::string& source_name);

void SaveCheckpoint(const std::string& path, const MappingSession& session);
MapperCheckpoint LoadCheckpoint(const std::string& path);
// LoadCheckpoint(path), or when that file is torn or corrupt, LoadCheckpoint(path.prev) with
// `warning` set to one line saying why; throws InputError naming both when neither loads.
MapperCheckpoint LoadCheckpointOrPrevious(const std::string& path, std::string* warning);
// A session resumed from a checkpoint, with the given options (grid cell size included).
MappingSession RestoreSession(const MappingSessionOptions& options, MapperCheckpoint checkpoint);

}  // namespace minenav::mapper
