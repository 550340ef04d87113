#include "logger/run_log.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "common/node/conversions.h"
#include "logger/strict_log_reader.h"
#include "logger/message_catalog.h"

namespace minenav {

namespace {

const std::string kScanType = "minenav.ladar_scan_t";
const std::string kOdometryType = "minenav.odometry_t";
const std::string kTruthType = "minenav.vehicle_truth_t";
const std::string kPoseType = "minenav.pose_estimate_t";

template <typename Msg>
Msg Decode(const LogRecord& rec, const std::string& where) {
  Msg msg{};
  std::string error;
  if (!DecodeMessage(rec.data.data(), static_cast<int>(rec.data.size()), rec.channel, &msg, &error))
    throw InputError(where + error);
  return msg;
}

}  // namespace

RunLog ReadRunLog(const std::string& path, const RunLogOptions& options) {
  RunLog run;
  StrictLogReader reader(path);
  LogRecord rec;
  while (reader.Next(&rec)) {
    if (std::find(run.channels.begin(), run.channels.end(), rec.channel) == run.channels.end())
      run.channels.push_back(rec.channel);
    const std::string where = path + ": event " + std::to_string(rec.eventnum) + " at byte " +
                              std::to_string(rec.offset) + ", channel " + rec.channel + ": ";
    const MessageProbe probe = ProbeMessage(rec.channel, rec.data.data(), rec.data.size());
    const bool wanted = probe.type_name == kScanType || probe.type_name == kOdometryType ||
                        probe.type_name == kTruthType || probe.type_name == kPoseType;
    if (!wanted) continue;
    if (!probe.ok) throw InputError(where + probe.error);
    try {
      if (probe.type_name == kScanType) {
        if (!options.read_scans) continue;
        LadarScan scan = FromLcm(Decode<ladar_scan_t>(rec, where));
        const std::string why = ValidateScan(scan);
        if (!why.empty()) throw InputError(why);
        run.scans[rec.channel].push_back(std::move(scan));
        continue;
      }
      StampedPose sp;
      if (probe.type_name == kOdometryType) {
        const OdometryReading o = FromLcm(Decode<odometry_t>(rec, where));
        sp = {o.utime, o.pose};
      } else if (probe.type_name == kTruthType) {
        const TruthReading t = FromLcm(Decode<vehicle_truth_t>(rec, where));
        sp = {t.utime, t.pose};
      } else {
        const PoseEstimate e = FromLcm(Decode<pose_estimate_t>(rec, where));
        sp = {e.utime, e.pose};
      }
      PoseTrack& track = run.tracks[rec.channel];
      track.channel = rec.channel;
      track.type = probe.type_name;
      track.poses.push_back(sp);
    } catch (const InputError& e) {
      const std::string what = e.what();
      throw InputError(what.rfind(path, 0) == 0 ? what : where + what);
    }
  }
  std::sort(run.channels.begin(), run.channels.end());
  return run;
}

std::optional<Pose2> PoseAt(const std::vector<StampedPose>& poses, int64_t utime, int64_t max_gap_us) {
  if (poses.empty()) return std::nullopt;
  // Logs are in receive order; sort a copy of the index only if needed.
  const bool sorted = std::is_sorted(poses.begin(), poses.end(),
                                     [](const StampedPose& a, const StampedPose& b) { return a.utime < b.utime; });
  std::vector<StampedPose> sorted_copy;
  const std::vector<StampedPose>* p = &poses;
  if (!sorted) {
    sorted_copy = poses;
    std::stable_sort(sorted_copy.begin(), sorted_copy.end(),
                     [](const StampedPose& a, const StampedPose& b) { return a.utime < b.utime; });
    p = &sorted_copy;
  }
  const auto it = std::lower_bound(p->begin(), p->end(), utime,
                                   [](const StampedPose& a, int64_t t) { return a.utime < t; });
  if (it != p->end() && it->utime == utime) return it->pose;
  if (it == p->begin() || it == p->end()) return std::nullopt;
  const StampedPose& a = *(it - 1);
  const StampedPose& b = *it;
  if (b.utime - a.utime > max_gap_us) return std::nullopt;
  const double s = static_cast<double>(utime - a.utime) / static_cast<double>(b.utime - a.utime);
  return InterpolatePose(a.pose, b.pose, s);
}

std::string ScansToCsv(const std::vector<LadarScan>& scans, bool valid_only) {
  std::ostringstream os;
  os << "utime,scan_id,index,bearing,range\n";
  for (const auto& scan : scans) {
    for (size_t i = 0; i < scan.ranges.size(); ++i) {
      if (valid_only && !scan.IsValid(i)) continue;
      os << scan.utime << "," << scan.scan_id << "," << i << "," << std::setprecision(9) << scan.Bearing(i) << ","
         << std::setprecision(7) << scan.ranges[i] << "\n";
    }
  }
  return os.str();
}

}  // namespace minenav
