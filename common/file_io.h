#pragma once
// File contracts of DESIGN.md ("File contracts"): segment maps (JSON), poses and scan
// stations (CSV). Readers validate everything and throw InputError with a one-line
// message naming file, line and what was wrong. Writers write to a temporary file and
// rename it, so a failed run never leaves a partial file that looks complete.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "common/pose2.h"

namespace minenav {

// Bad input from outside (file, flag, message): the message is one line for the user.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

std::string ReadFile(const std::string& path);
// Throws InputError when `output` names the same file as one of `inputs` (also through a
// different spelling of the path or a link), so a run can never overwrite what it reads.
// `what` names the output option in the message, e.g. "--map-out". Empty paths are ignored.
void CheckOutputIsNotInput(const std::string& what, const std::string& output,
                           const std::vector<std::string>& inputs);
// How WriteFileAtomically guards the file against a crash or a power cut.
struct AtomicWriteOptions {
  // fsync the new file before the rename and the folder after it: once the call returns the
  // content survives a power cut (a plain rename can leave an empty file after one on ext4).
  bool durable = false;
  // The file it replaces stays as PATH.prev (a hard link, made before the rename): if PATH is
  // ever found torn or corrupt, the one before it is still there.
  bool keep_previous = false;
  // >= 0 (e.g. 0600 for a key file): the file has this mode from its creation, before any byte
  // is written, whatever the umask; -1: 0644 less the umask.
  int mode = -1;
};
// Writes `content` to path.tmp.<pid> and renames it onto `path`: a crash mid-write leaves
// the previous file whole. A path that is a device or a pipe (/dev/null, a FIFO) is written in
// place (renaming would replace the device); a folder is an InputError.
void WriteFileAtomically(const std::string& path, const std::string& content, const AtomicWriteOptions& options = {});
// PATH.prev, the file WriteFileAtomically kept with keep_previous.
std::string PreviousFilePath(const std::string& path);

// {"segments": [[x1, y1, x2, y2], ...]} in metres; other keys are allowed and ignored.
std::vector<Segment> ParseSegmentsJson(const std::string& text, const std::string& source_name);
std::vector<Segment> LoadSegmentsJson(const std::string& path);
std::string SegmentsToJson(const std::vector<Segment>& segments);
void SaveSegmentsJson(const std::string& path, const std::vector<Segment>& segments);

// What a row of a poses CSV is (its fifth column, `status`): an estimate, or the guess an
// estimator started from and could not confirm. The same column in every estimator's and the
// mapper's --poses-out, so a scorer can leave the guesses out (evaluation/relations.h).
enum class PoseStatus {
  kEstimated,     // "estimated": an estimator's converged answer (IPE, FPE); a 4-column file's rows
  kInserted,      // "inserted": a scan the mapper inserted, at its refined pose
  kTracked,       // "tracked": a scan the mapper tracked against its map
  kNotConverged,  // "not_converged": no estimate: the initial pose the match started from
};
const char* PoseStatusName(PoseStatus status);
// False only for kNotConverged.
bool IsEstimate(PoseStatus status);
// An estimator's row: kEstimated when its match converged, else kNotConverged.
PoseStatus EstimatorPoseStatus(bool converged);

// Poses CSV, header utime,x,y,theta,status (or utime,x,y,theta: every row estimated): one row
// per scan, theta in radians.
struct StampedPose {
  int64_t utime = 0;
  Pose2 pose;
  PoseStatus status = PoseStatus::kEstimated;
};
std::vector<StampedPose> ParsePosesCsv(const std::string& text, const std::string& source_name);
std::vector<StampedPose> LoadPosesCsv(const std::string& path);
std::string PosesToCsv(const std::vector<StampedPose>& poses);
void SavePosesCsv(const std::string& path, const std::vector<StampedPose>& poses);

// Scan stations CSV, header x,y,theta with an optional fourth column `world` (index into
// a list of worlds, default 0).
struct Station {
  Pose2 pose;
  int world = 0;
};
std::vector<Station> ParseStationsCsv(const std::string& text, const std::string& source_name);
std::vector<Station> LoadStationsCsv(const std::string& path);
std::string StationsToCsv(const std::vector<Station>& stations);
void SaveStationsCsv(const std::string& path, const std::vector<Station>& stations);

}  // namespace minenav
