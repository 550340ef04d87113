#include "evaluation/relations.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>

#include "common/angle.h"
#include "common/pose_at_time.h"
#include "dataset_readers/carmen_log.h"

namespace minenav {
namespace {

double ParseField(const std::string& field, const std::string& where, const char* name) {
  double v = 0.0;
  const auto r = std::from_chars(field.data(), field.data() + field.size(), v);
  if (r.ec != std::errc() || r.ptr != field.data() + field.size() || !std::isfinite(v))
    throw InputError(where + ": " + name + " '" + field + "' is not a finite number");
  return v;
}

int64_t ToMicros(double seconds) { return std::llround(seconds * 1e6); }

std::vector<StampedPose> SortedByTime(const std::vector<StampedPose>& poses) {
  std::vector<StampedPose> sorted = poses;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const StampedPose& a, const StampedPose& b) { return a.utime < b.utime; });
  return sorted;
}

// The estimate whose time is nearest `utime` (sorted input, not empty).
const StampedPose& Nearest(const std::vector<StampedPose>& sorted, int64_t utime) {
  const auto after = std::lower_bound(sorted.begin(), sorted.end(), utime,
                                      [](const StampedPose& p, int64_t t) { return p.utime < t; });
  if (after == sorted.begin()) return *after;
  if (after == sorted.end()) return *std::prev(after);
  const auto before = std::prev(after);
  return (utime - before->utime) <= (after->utime - utime) ? *before : *after;
}

struct PoseLookup {
  Pose2 pose;
  bool corrected = false;
};

}  // namespace

std::vector<Relation> ParseRelations(const std::string& text, const std::string& source_name) {
  std::vector<Relation> relations;
  std::istringstream in(text);
  std::string line;
  int64_t line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    std::istringstream fields_in(line);
    std::vector<std::string> f;
    for (std::string field; fields_in >> field;) f.push_back(field);
    if (f.empty() || f[0][0] == '#') continue;
    const std::string where = source_name + ":" + std::to_string(line_number);
    if (f.size() != 8)
      throw InputError(where + ": expected 8 fields (t1 t2 x y z roll pitch yaw), got " + std::to_string(f.size()));
    Relation r;
    if (!ParseCarmenTimestamp(f[0], &r.utime1)) throw InputError(where + ": t1 '" + f[0] + "' is not a time in seconds");
    if (!ParseCarmenTimestamp(f[1], &r.utime2)) throw InputError(where + ": t2 '" + f[1] + "' is not a time in seconds");
    const double x = ParseField(f[2], where, "x");
    const double y = ParseField(f[3], where, "y");
    ParseField(f[4], where, "z");
    ParseField(f[5], where, "roll");
    ParseField(f[6], where, "pitch");
    const double yaw = ParseField(f[7], where, "yaw");
    r.delta = Pose2(x, y, NormalizeAngle(yaw));
    relations.push_back(r);
  }
  return relations;
}

std::vector<Relation> LoadRelations(const std::string& path) { return ParseRelations(ReadFile(path), path); }

ErrorStatistic MeanAndSampleStd(const std::vector<double>& values) {
  ErrorStatistic s;
  if (values.empty()) return s;
  double sum = 0.0;
  for (double v : values) sum += v;
  s.mean = sum / static_cast<double>(values.size());
  if (values.size() < 2) return s;
  double ss = 0.0;
  for (double v : values) ss += (v - s.mean) * (v - s.mean);
  s.std = std::sqrt(ss / static_cast<double>(values.size() - 1));
  return s;
}

RelationScore ScoreRelations(const std::vector<Relation>& relations, const std::vector<StampedPose>& estimates,
                             const std::vector<StampedPose>& odometry, const RelationOptions& options) {
  RelationScore score;
  score.relations = static_cast<int64_t>(relations.size());
  if (!(options.max_time_gap >= 0.0) || !(options.max_odometry_gap >= 0.0)) {
    score.reason = "max_time_gap and max_odometry_gap must be >= 0";
    return score;
  }
  if (relations.empty()) {
    score.reason = "no relations";
    return score;
  }
  // A row that is no estimate (the initial pose of a match that did not converge) is left out:
  // a relation at its time is scored from the estimates around it, or skipped.
  std::vector<StampedPose> kept;
  kept.reserve(estimates.size());
  for (const StampedPose& p : estimates) {
    if (IsEstimate(p.status))
      kept.push_back(p);
    else
      ++score.not_estimates;
  }
  if (kept.empty()) {
    score.reason = estimates.empty() ? "no estimated poses"
                                     : "no estimated poses (" + std::to_string(score.not_estimates) +
                                           " rows not converged)";
    return score;
  }
  const std::vector<StampedPose> est = SortedByTime(kept);
  const std::vector<StampedPose> odo = SortedByTime(odometry);
  const int64_t max_gap = ToMicros(options.max_time_gap);
  const int64_t max_odo_gap = ToMicros(options.max_odometry_gap);

  auto pose_at = [&](int64_t utime) -> std::optional<PoseLookup> {
    const StampedPose& e = Nearest(est, utime);
    if (std::llabs(e.utime - utime) <= max_gap) return PoseLookup{e.pose, false};
    const std::optional<Pose2> o_e = PoseAtTime(odo, e.utime, max_odo_gap);
    const std::optional<Pose2> o_t = PoseAtTime(odo, utime, max_odo_gap);
    if (!o_e || !o_t) return std::nullopt;
    return PoseLookup{e.pose * Between(*o_e, *o_t), true};
  };

  std::vector<double> trans, trans2, rot, rot2;
  for (const Relation& r : relations) {
    const std::optional<PoseLookup> p1 = pose_at(r.utime1);
    const std::optional<PoseLookup> p2 = pose_at(r.utime2);
    if (!p1 || !p2) {
      ++score.skipped;
      continue;
    }
    const Pose2 delta = Between(p1->pose, p2->pose);
    RelationErrorEntry entry;
    entry.relation = r;
    entry.translation_error = std::hypot(delta.x - r.delta.x, delta.y - r.delta.y);
    entry.rotation_error = std::abs(NormalizeAngle(delta.theta - r.delta.theta));
    entry.odometry_corrected = p1->corrected || p2->corrected;
    if (entry.odometry_corrected) ++score.odometry_corrected;
    const double rot_deg = RadToDeg(entry.rotation_error);
    trans.push_back(entry.translation_error);
    trans2.push_back(entry.translation_error * entry.translation_error);
    rot.push_back(rot_deg);
    rot2.push_back(rot_deg * rot_deg);
    score.entries.push_back(entry);
  }
  score.n = static_cast<int64_t>(score.entries.size());
  if (score.n == 0) {
    score.reason = "no relation has an estimate within " + std::to_string(options.max_time_gap) +
                   " s of both its times" + (odometry.empty() ? " (and no odometry to correct with)" : " or odometry to correct with");
    return score;
  }
  score.ok = true;
  score.translation = MeanAndSampleStd(trans);
  score.translation_squared = MeanAndSampleStd(trans2);
  score.rotation = MeanAndSampleStd(rot);
  score.rotation_squared = MeanAndSampleStd(rot2);
  return score;
}

}  // namespace minenav
