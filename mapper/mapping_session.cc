#include "mapper/mapping_session.h"

#include <cmath>
#include <sstream>

#include "common/angle.h"

namespace minenav::mapper {

std::string ValidateOptions(const MappingSessionOptions& o) {
  if (std::string why = ValidateOptions(o.mapper); !why.empty()) return why;
  std::ostringstream why;
  if (!(o.insert_min_translation >= 0.0) || !std::isfinite(o.insert_min_translation))
    why << "insert_min_translation must be >= 0 m, got " << o.insert_min_translation;
  else if (!(o.insert_min_rotation >= 0.0) || !std::isfinite(o.insert_min_rotation))
    why << "insert_min_rotation must be >= 0 rad, got " << o.insert_min_rotation;
  else if (o.refine_every_inserts < 0)
    why << "refine_every_inserts must be >= 0, got " << o.refine_every_inserts;
  return why.str();
}

void DeclareOptions(OptionScope s, MappingSessionOptions& o) {
  DeclareOptions(s.Nested("mapper"), o.mapper);
  s.AddDouble("insert_min_translation", &o.insert_min_translation, "m",
              "insert a scan when the vehicle moved this far since the last inserted one, track the others (their "
              "poses are reported, the map is untouched); 0 = off; both off = insert every scan (survey)",
              0.0, 1000.0);
  s.AddDouble("insert_min_rotation", &o.insert_min_rotation, "rad",
              "insert a scan when the heading changed this much since the last inserted one; 0 = off",
              0.0, 3.2);
  s.AddInt("refine_every_inserts", &o.refine_every_inserts,
           "concurrent refinement after every this many inserts, at a deterministic point of the scan sequence; "
           "0 = only when asked (at the end) [inserts]",
           0, 1000000);
}

const char* ToString(ScanOutcome outcome) {
  switch (outcome) {
    case ScanOutcome::kInserted:
      return "inserted";
    case ScanOutcome::kTracked:
      return "tracked";
    case ScanOutcome::kRefused:
      return "refused";
  }
  return "?";
}

MappingSession::MappingSession(MappingSessionOptions options)
    : options_(std::move(options)), mapper_(options_.mapper) {}

MappingSession::MappingSession(MappingSessionOptions options, ContourMap map) : MappingSession(std::move(options)) {
  mapper_.SetMap(std::move(map));
}

MappingSession::MappingSession(MappingSessionOptions options, ContourMap map, std::vector<MappedScan> scans,
                               MappingSessionState state)
    : MappingSession(std::move(options)) {
  mapper_.RestoreState(std::move(map), std::move(scans));
  state_ = std::move(state);
}

namespace {

// The refusal tests of ContourMapper::InsertPreprocessed (contour_mapper.cc), for scans that
// are only tracked: a tracked pose must be as trustworthy as an inserted one.
std::string RefusalReason(const PoseEstimationResult& e, const Pose2& initial, const ContourMapperOptions& o) {
  std::ostringstream why;
  if (e.fit.num_pieces < o.pose.min_pieces)
    why << "no overlap with the map: " << e.status;
  else if (e.fit.MatchedFraction() < o.min_overlap_fraction)
    why << "too little overlap with the map (" << 100.0 * e.fit.MatchedFraction() << "% of points match)";
  else if (TranslationDistance(initial, e.pose) > o.max_correction_translation ||
           HeadingDistance(initial, e.pose) > o.max_correction_rotation)
    why << "correction too large (" << TranslationDistance(initial, e.pose) << " m, "
        << RadToDeg(HeadingDistance(initial, e.pose)) << " deg): initial estimate too far off";
  else if (std::sqrt(e.fit.MeanSquaredDistance()) > o.max_rms_distance)
    why << "poor fit (RMS " << std::sqrt(e.fit.MeanSquaredDistance()) << " m)";
  return why.str();
}

void CopyFit(const PoseEstimationResult& e, ScanResult* out) {
  out->num_inliers = e.num_inliers;
  out->iterations = e.iterations;
  out->residual = e.residual;
}

// An accepted scan reports "ok: inserted" or "ok: tracked" as its status (what POSE
// carries); what the estimate and the insert said is kept as the summary.
void Accept(ScanOutcome outcome, std::string summary, ScanResult* out) {
  out->outcome = outcome;
  out->converged = true;
  out->status = std::string("ok: ") + ToString(outcome);
  out->summary = std::move(summary);
}

}  // namespace

ScanResult MappingSession::Track(PreprocessedScan scan, ScanResult out) const {
  const PoseEstimationResult e = EstimatePose(scan, out.initial, mapper_.map(), options_.mapper.pose);
  out.pose = e.pose;
  CopyFit(e, &out);
  if (std::string why = RefusalReason(e, out.initial, options_.mapper); !why.empty()) {
    out.pose = out.initial;
    out.status = std::move(why);
    return out;
  }
  Accept(ScanOutcome::kTracked, e.status, &out);
  return out;
}

ScanResult MappingSession::AddScan(const LadarScan& scan, const Pose2& odometry) {
  ScanResult out;
  out.utime = scan.utime;
  out.scan_id = scan.scan_id;
  out.initial = state_.has_anchor ? state_.anchor_pose * Between(state_.anchor_odometry, odometry) : odometry;
  out.pose = out.initial;
  std::string invalid;
  if (!std::isfinite(odometry.x) || !std::isfinite(odometry.y) || !std::isfinite(odometry.theta)) {
    invalid = "odometry pose is not finite";
  } else if (const std::string why = ValidateScan(scan); !why.empty()) {
    invalid = "invalid scan: " + why;
  }
  if (!invalid.empty()) {
    out.status = std::move(invalid);
    ++state_.refused;
    return out;
  }
  PreprocessedScan pre = PreprocessScan(scan, options_.mapper.preprocessing);
  out.num_points = pre.NumPoints();

  const std::vector<MappedScan>& scans = mapper_.scans();
  bool insert = scans.empty();
  if (!insert) {
    const bool by_translation = options_.insert_min_translation > 0.0;
    const bool by_rotation = options_.insert_min_rotation > 0.0;
    const Pose2& last = scans.back().pose;
    insert = (!by_translation && !by_rotation) ||
             (by_translation && TranslationDistance(last, out.initial) >= options_.insert_min_translation) ||
             (by_rotation && HeadingDistance(last, out.initial) >= options_.insert_min_rotation);
  }

  if (insert && scans.empty() && mapper_.map().NumContours() > 0) {
    // A loaded map and no scan yet: localise first, then this scan anchors the frame at
    // its estimate (the mapper keeps its first scan where it is given).
    if (out.num_points < options_.mapper.min_scan_points) {
      out.status = "too few usable points (" + std::to_string(out.num_points) + " < " +
                   std::to_string(options_.mapper.min_scan_points) + ")";
      ++state_.refused;
      return out;
    }
    const ScanResult located = Track(pre, out);
    if (!located.accepted()) {
      ++state_.refused;
      return located;
    }
    out.initial = located.pose;
  }

  if (!insert) {
    if (out.num_points < options_.mapper.min_scan_points) {
      out.status = "too few usable points (" + std::to_string(out.num_points) + " < " +
                   std::to_string(options_.mapper.min_scan_points) + ")";
      ++state_.refused;
      return out;
    }
    out = Track(std::move(pre), out);
    if (!out.accepted()) {
      ++state_.refused;
      return out;
    }
    ++state_.tracked;
    state_.has_anchor = true;
    state_.anchor_pose = out.pose;
    state_.anchor_odometry = odometry;
    state_.anchor_scan_index = -1;
    state_.poses.push_back({out.utime, -1, out.pose});
    return out;
  }

  const InsertResult r = mapper_.InsertPreprocessed(std::move(pre), out.initial);
  out.pose = r.pose;
  CopyFit(r.estimation, &out);
  if (!r.accepted) {
    out.pose = out.initial;
    out.status = r.reason;
    ++state_.refused;
    return out;
  }
  Accept(ScanOutcome::kInserted, r.reason, &out);
  out.scan_index = r.scan_index;
  ++state_.inserted;
  state_.has_anchor = true;
  state_.anchor_pose = out.pose;
  state_.anchor_odometry = odometry;
  state_.anchor_scan_index = r.scan_index;
  state_.poses.push_back({out.utime, r.scan_index, out.pose});
  ++state_.inserts_since_refine;
  if (options_.refine_every_inserts > 0 && state_.inserts_since_refine >= options_.refine_every_inserts) {
    out.refinement = Refine();
    out.refined = true;
    out.pose = mapper_.scans()[static_cast<size_t>(r.scan_index)].pose;
  }
  return out;
}

ConcurrentRefinementResult MappingSession::Refine() { return AfterRefine(mapper_.Refine()); }

ConcurrentRefinementResult MappingSession::Refine(const ShouldStop& should_stop) {
  return AfterRefine(mapper_.Refine(should_stop));
}

ConcurrentRefinementResult MappingSession::RefineWith(const ConcurrentRefinementOptions& refinement) {
  return AfterRefine(mapper_.RefineWith(refinement));
}

ConcurrentRefinementResult MappingSession::AfterRefine(ConcurrentRefinementResult r) {
  // A stopped refinement is still due: a run resumed from a checkpoint of this state does
  // it at its next insert.
  if (!r.stopped) state_.inserts_since_refine = 0;
  // The next initial estimate composes onto the anchor's refined pose.
  if (state_.anchor_scan_index >= 0)
    state_.anchor_pose = mapper_.scans()[static_cast<size_t>(state_.anchor_scan_index)].pose;
  return r;
}

std::vector<StampedPose> MappingSession::Poses() const {
  std::vector<StampedPose> out;
  out.reserve(state_.poses.size());
  for (const SessionPose& p : state_.poses)
    out.push_back(p.scan_index >= 0
                      ? StampedPose{p.utime, mapper_.scans()[static_cast<size_t>(p.scan_index)].pose, PoseStatus::kInserted}
                      : StampedPose{p.utime, p.pose, PoseStatus::kTracked});
  return out;
}

}  // namespace minenav::mapper
