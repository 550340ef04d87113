#pragma once
// The parts of a log that describe a run: ladar scans and pose tracks (ODOMETRY,
// SIM_TRUTH, POSE*), decoded into plain types for export and rendering.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/file_io.h"
#include "common/scan.h"

namespace minenav {

struct PoseTrack {
  std::string channel;
  std::string type;  // minenav.odometry_t, minenav.vehicle_truth_t or minenav.pose_estimate_t
  std::vector<StampedPose> poses;  // in log order
};

struct RunLog {
  std::map<std::string, std::vector<LadarScan>> scans;  // by channel, in log order
  std::map<std::string, PoseTrack> tracks;              // by channel
  std::vector<std::string> channels;                    // every channel seen, sorted
};

struct RunLogOptions {
  bool read_scans = true;  // false skips decoding scans (faster when only poses are needed)
};

// Reads every message whose type is a scan or a pose (found by fingerprint, and by
// channel name for the channels DESIGN.md names). Throws InputError (one line, naming
// channel and byte offset) for a damaged file or a message on those channels that does
// not decode or holds invalid values. Messages of other types are skipped.
RunLog ReadRunLog(const std::string& path, const RunLogOptions& options = {});

// The pose of a track at `utime`: exact match, else linear interpolation between the
// poses around it (heading on the shorter arc) when they are at most `max_gap_us` apart.
std::optional<Pose2> PoseAt(const std::vector<StampedPose>& poses, int64_t utime, int64_t max_gap_us);

// Scans CSV: header utime,scan_id,index,bearing,range, one row per reading (bearing in
// rad in the sensor frame, range in m; invalid readings as written, e.g. nan).
std::string ScansToCsv(const std::vector<LadarScan>& scans, bool valid_only);

}  // namespace minenav
