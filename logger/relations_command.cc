// log_tool relations: scores estimated robot poses against a relations file with the
// Kuemmerle 2009 metric in Freiburg metricEvaluator's form (relations.h).

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/file_io.h"
#include "common/node/conversions.h"
#include "common/node/event_log.h"
#include "dataset_readers/carmen_log.h"
#include "logger/log_tool_commands.h"
#include "evaluation/relations.h"

namespace minenav {
namespace {

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Poses of one channel of an LCM log: odometry_t, pose_estimate_t or vehicle_truth_t
// (whichever the payload decodes as).
std::vector<StampedPose> PosesFromLcmLog(const std::string& path, const std::string& channel) {
  LogReader reader(path);
  std::vector<StampedPose> poses;
  int64_t bad = 0;
  std::string first_error;
  while (const LogEvent* e = reader.NextInPlace()) {
    if (e->channel != channel) continue;
    const int size = static_cast<int>(e->data.size());
    std::string error;
    odometry_t odo{};
    pose_estimate_t est{};
    vehicle_truth_t truth{};
    try {
      if (DecodeMessage(e->data.data(), size, channel, &odo, &error)) {
        const OdometryReading r = FromLcm(odo);
        poses.push_back({r.utime, r.pose});
      } else if (DecodeMessage(e->data.data(), size, channel, &est, &error)) {
        const PoseEstimate r = FromLcm(est);
        poses.push_back({r.utime, r.pose, EstimatorPoseStatus(r.converged)});
      } else if (DecodeMessage(e->data.data(), size, channel, &truth, &error)) {
        const TruthReading r = FromLcm(truth);
        poses.push_back({r.utime, r.pose});
      } else {
        ++bad;
        if (first_error.empty()) first_error = channel + ": not odometry_t, pose_estimate_t or vehicle_truth_t";
      }
    } catch (const InputError& err) {
      ++bad;
      if (first_error.empty()) first_error = err.what();
    }
  }
  if (bad > 0)
    std::fprintf(stderr, "log_tool relations: %s: %lld messages on %s skipped (first: %s)\n", path.c_str(),
                 static_cast<long long>(bad), channel.c_str(), first_error.c_str());
  if (poses.empty()) throw InputError(path + ": no poses on channel " + channel);
  return poses;
}

std::vector<StampedPose> ToStamped(const std::vector<OdometryReading>& readings, int64_t shift_us) {
  std::vector<StampedPose> poses;
  poses.reserve(readings.size());
  for (const OdometryReading& r : readings) poses.push_back({r.utime + shift_us, r.pose});
  return poses;
}

// A poses CSV, an LCM log (channel), or a CARMEN log (robot poses of its laser lines, or
// with `odometry_lines` its ODOM lines when it has any).
std::vector<StampedPose> LoadPoses(const std::string& path, const std::string& lcm_channel, bool odometry_lines) {
  if (EndsWith(path, ".csv")) return LoadPosesCsv(path);
  if (EndsWith(path, ".lcm")) return PosesFromLcmLog(path, lcm_channel);
  const CarmenLog log = ReadCarmenLog(path);
  if (odometry_lines && !log.odometry.empty()) return ToStamped(log.odometry, 0);
  if (log.scan_odometry.empty()) throw InputError(path + ": no FLASER or ROBOTLASER1 lines");
  return ToStamped(log.scan_odometry, 0);
}

std::string FormatScore(const RelationScore& s) {
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "relations %lld, scored %lld, skipped %lld, odometry-corrected %lld\n"
                "%-22s %12s %12s\n"
                "%-22s %12.4f %12.4f\n"
                "%-22s %12.5f %12.5f\n"
                "%-22s %12.3f %12.3f\n"
                "%-22s %12.3f %12.3f\n",
                static_cast<long long>(s.relations), static_cast<long long>(s.n), static_cast<long long>(s.skipped),
                static_cast<long long>(s.odometry_corrected), "error", "mean", "std", "translation (m)",
                s.translation.mean, s.translation.std, "translation^2 (m^2)", s.translation_squared.mean,
                s.translation_squared.std, "rotation (deg)", s.rotation.mean, s.rotation.std, "rotation^2 (deg^2)",
                s.rotation_squared.mean, s.rotation_squared.std);
  std::string text = buf;
  // A poses file's rows that are no estimates (status not_converged) were left out.
  if (s.not_estimates > 0)
    text = "poses left out: " + std::to_string(s.not_estimates) + " rows not converged\n" + text;
  return text;
}

nlohmann::json ScoreToJson(const RelationScore& s, const std::string& relations, const std::string& poses,
                           const std::string& odometry, const RelationOptions& o) {
  auto stat = [](const ErrorStatistic& e) { return nlohmann::json{{"mean", e.mean}, {"std", e.std}}; };
  return nlohmann::json{{"relations_file", relations},
                        {"poses", poses},
                        {"odometry", odometry},
                        {"max_time_gap_s", o.max_time_gap},
                        {"max_odometry_gap_s", o.max_odometry_gap},
                        {"relations", s.relations},
                        {"n", s.n},
                        {"skipped", s.skipped},
                        {"odometry_corrected", s.odometry_corrected},
                        {"poses_not_converged", s.not_estimates},
                        {"translation_m", stat(s.translation)},
                        {"translation_squared_m2", stat(s.translation_squared)},
                        {"rotation_deg", stat(s.rotation)},
                        {"rotation_squared_deg2", stat(s.rotation_squared)}};
}

}  // namespace

int RunRelationsCommand(const std::vector<std::string>& args) {
  std::string relations_path, poses_path, odometry_path, json_out, errors_out;
  std::string poses_channel = "POSE", odometry_channel = "ODOMETRY";
  double time_shift = 0.0;
  RelationOptions options;
  ConfigSchema schema(
      "log_tool relations",
      "Scores estimated robot poses against a relations file (t1 t2 x y z roll pitch yaw) with the\n"
      "metric of Kuemmerle et al. 2009 as Freiburg's metricEvaluator computes it: the estimate nearest\n"
      "each relation time (within --max-time-gap, else moved on by the odometry), delta = P(t1)^-1 P(t2),\n"
      "translational error |t_delta - t_delta*|, rotational error the wrapped yaw difference. Prints N and\n"
      "the mean and sample std of the absolute and squared errors (m, m^2, deg, deg^2).");
  schema.AddString("relations", &relations_path, "relations file (required)");
  schema.AddString("poses", &poses_path,
                   "estimated robot poses (required): poses CSV utime,x,y,theta[,status] (.csv; rows not_converged left out); an LCM log (.lcm,\n"
                   "channel --poses-channel); or a CARMEN log (the robot poses of its laser lines: the raw\n"
                   "log scores raw odometry, a corrected log scores its corrections)");
  schema.AddString("poses_channel", &poses_channel,
                   "channel of the poses in an LCM log (odometry_t, pose_estimate_t or vehicle_truth_t)");
  schema.AddDouble("poses_time_shift", &time_shift, "s",
                   "added to every pose time (intel-corrected.log.gz: 976052857.337284)", -1e10, 1e10);
  schema.AddString("odometry", &odometry_path,
                   "odometry for estimates farther than --max-time-gap from a relation time: an LCM log\n"
                   "(.lcm, channel --odometry-channel) or a CARMEN log (ODOM lines, else laser-line poses)");
  schema.AddString("odometry_channel", &odometry_channel, "channel of the odometry in an LCM log");
  schema.AddDouble("max_time_gap", &options.max_time_gap, "s",
                   "an estimate this close to a relation time is used as is", 0.0, 1e6);
  schema.AddDouble("max_odometry_gap", &options.max_odometry_gap, "s",
                   "odometry readings may be up to twice this apart to interpolate between", 0.0, 1e6);
  schema.AddString("json_out", &json_out, "also write the score as JSON to this file");
  schema.AddString("errors_out", &errors_out,
                   "write the per-relation errors as CSV (t1,t2,translation_m,rotation_deg,odometry_corrected)");
  schema.AddHelpEpilog(
      "Example: log_tool relations --relations intel.relations.txt --poses intel.clf.bz2\n"
      "         (raw odometry: every relation time is a FLASER time)\n");
  if (schema.Parse(args) == ParseOutcome::kExit) return 0;
  RequireOutputPath(relations_path, "--relations");
  RequireOutputPath(poses_path, "--poses");
  const std::vector<std::string> inputs = {relations_path, poses_path, odometry_path};
  CheckOutputIsNotInput("--json-out", json_out, inputs);
  CheckOutputIsNotInput("--errors-out", errors_out, inputs);

  const std::vector<Relation> relations = LoadRelations(relations_path);
  std::vector<StampedPose> poses = LoadPoses(poses_path, poses_channel, false);
  const int64_t shift_us = std::llround(time_shift * 1e6);
  for (StampedPose& p : poses) p.utime += shift_us;
  std::vector<StampedPose> odometry;
  if (!odometry_path.empty()) odometry = LoadPoses(odometry_path, odometry_channel, true);
  const RelationScore score = ScoreRelations(relations, poses, odometry, options);
  if (!score.ok) throw InputError("nothing scored: " + score.reason);
  std::fprintf(stderr, "log_tool relations: %zu relations, %zu poses, %zu odometry readings\n", relations.size(),
               poses.size(), odometry.size());
  std::fputs(FormatScore(score).c_str(), stdout);
  if (!json_out.empty())
    WriteFileAtomically(json_out, ScoreToJson(score, relations_path, poses_path, odometry_path, options).dump(2) + "\n");
  if (!errors_out.empty()) {
    std::string csv = "t1,t2,translation_m,rotation_deg,odometry_corrected\n";
    char line[160];
    for (const RelationErrorEntry& e : score.entries) {
      std::snprintf(line, sizeof line, "%.6f,%.6f,%.6f,%.6f,%d\n", static_cast<double>(e.relation.utime1) * 1e-6,
                    static_cast<double>(e.relation.utime2) * 1e-6, e.translation_error, RadToDeg(e.rotation_error),
                    e.odometry_corrected ? 1 : 0);
      csv += line;
    }
    WriteFileAtomically(errors_out, csv);
  }
  return 0;
}

}  // namespace minenav
