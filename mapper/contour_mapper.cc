#include "mapper/contour_mapper.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "mapper/correspondence.h"

namespace minenav::mapper {

std::string ValidateOptions(const ContourMapperOptions& o) {
  if (std::string why = ValidateOptions(o.preprocessing); !why.empty()) return "preprocessing: " + why;
  if (std::string why = ValidateOptions(o.pose); !why.empty()) return "pose: " + why;
  if (std::string why = ValidateOptions(o.expansion); !why.empty()) return "expansion: " + why;
  if (std::string why = ValidateOptions(o.disappearance); !why.empty()) return "disappearance: " + why;
  if (std::string why = ValidateOptions(o.fitting); !why.empty()) return "fitting: " + why;
  if (std::string why = ValidateOptions(o.refinement); !why.empty()) return "refinement: " + why;
  std::ostringstream why;
  if (!(o.grid_cell_size > 0.0))
    why << "grid_cell_size must be > 0 m, got " << o.grid_cell_size;
  else if (o.min_scan_points < 2)
    why << "min_scan_points must be >= 2, got " << o.min_scan_points;
  else if (!(o.min_overlap_fraction >= 0.0 && o.min_overlap_fraction <= 1.0))
    why << "min_overlap_fraction must be in [0, 1], got " << o.min_overlap_fraction;
  else if (!(o.max_correction_translation > 0.0) || !(o.max_correction_rotation > 0.0))
    why << "max_correction_translation and max_correction_rotation must be > 0";
  else if (!(o.max_rms_distance > 0.0))
    why << "max_rms_distance must be > 0 m, got " << o.max_rms_distance;
  return why.str();
}

void DeclareOptions(OptionScope s, ContourMapperOptions& o) {
  DeclareOptions(s.Nested("preprocessing"), o.preprocessing);
  DeclareOptions(s.Nested("pose"), o.pose);
  DeclareOptions(s.Nested("expansion"), o.expansion);
  DeclareOptions(s.Nested("disappearance"), o.disappearance);
  DeclareOptions(s.Nested("fitting"), o.fitting);
  DeclareOptions(s.Nested("refinement"), o.refinement);
  s.AddDouble("grid_cell_size", &o.grid_cell_size, "m",
              "cell of the contour map's segment grid; 2 m, four 0.5 m segments, so a query near a scan "
              "point visits few cells",
              0.01, 1000.0);
  s.AddInt("min_scan_points", &o.min_scan_points,
           "a scan with fewer usable points (after preprocessing) is refused; 50, 30 for 180-degree "
           "SICK scans [points]",
           2, 10000000);
  s.AddDouble("min_overlap_fraction", &o.min_overlap_fraction, "1",
              "fraction of a scan's points that must match the map after estimation, else it is refused; 0.15",
              0.0, 1.0);
  s.AddDouble("max_correction_translation", &o.max_correction_translation, "m",
              "refuse a scan whose estimate moves farther than this from its initial pose (it locked onto the "
              "wrong walls); 2 m, beyond a survey's dead-reckoning error",
              0.01, 100.0);
  s.AddDouble("max_correction_rotation", &o.max_correction_rotation, "rad",
              "refuse a scan whose estimate turns farther than this from its initial pose; 0.35 rad (20 "
              "degrees)",
              0.001, 3.2);
  s.AddDouble("max_rms_distance", &o.max_rms_distance, "m",
              "refuse a scan whose RMS distance to the contours it matched stays above this; 0.06 m, "
              "above the Typhoon's 4.4 cm noise",
              0.001, 10.0);
  s.AddDouble("local_fit_margin", &o.local_fit_margin, "m",
              "after an insert only vertices within the scan's bounding box grown by this are refitted, so the rest "
              "of the map keeps its shape and an insert stays local; < 0 = whole contours; 1 m",
              -1.0, 1000.0);
  s.AddDouble("local_fit_radius", &o.local_fit_radius, "m",
              "and only vertices within this distance of the new scan's sensor (along x and y) are refitted: a far "
              "wall the scan sees sparsely keeps the shape the scans near it gave it; 0 = the scan's box alone",
              0.0, 1000.0);
  s.AddInt("fit_scans", &o.fit_scans,
           "an insert refits the contours with the new scan and the scans taken nearest to it, this many in all; "
           "0 = every mapped scan (the thesis: an insert's cost grows with the map); 20 keeps a live mapper's "
           "inserts flat (mapper/README.md, \"Insert cost\") [scans]",
           0, 1000000);
  s.AddBool("refine_after_each_scan", &o.refine_after_each_scan,
            "concurrent refinement after every accepted scan (4.7: most accurate, slow); off: refine "
            "periodically or at the end");
}

std::vector<MappedScan> NearestScans(const std::vector<MappedScan>& scans, int count) {
  std::vector<MappedScan> out;
  if (scans.empty() || count <= 0) return out;
  const Eigen::Vector2d here = scans.back().pose * scans.back().scan.sensor_position;
  std::vector<std::pair<double, size_t>> by_distance;
  by_distance.reserve(scans.size());
  for (size_t k = 0; k < scans.size(); ++k)
    by_distance.emplace_back((scans[k].pose * scans[k].scan.sensor_position - here).squaredNorm(), k);
  const size_t n = std::min(by_distance.size(), static_cast<size_t>(count));
  // Ties (a survey's scans taken at one station) keep the later scan first.
  std::partial_sort(by_distance.begin(), by_distance.begin() + static_cast<std::ptrdiff_t>(n), by_distance.end(),
                    [](const auto& a, const auto& b) { return a.first < b.first || (a.first == b.first && a.second > b.second); });
  std::vector<size_t> chosen;
  for (size_t k = 0; k < n; ++k) chosen.push_back(by_distance[k].second);
  std::sort(chosen.begin(), chosen.end());  // in the order they were mapped
  out.reserve(n);
  for (const size_t k : chosen) out.push_back(scans[k]);
  return out;
}

ContourMapper::ContourMapper(ContourMapperOptions options)
    : options_(std::move(options)), map_(options_.grid_cell_size) {}

InsertResult ContourMapper::InsertScan(const LadarScan& scan, const Pose2& initial, const InsertOptions& insert) {
  if (const std::string why = ValidateScan(scan); !why.empty()) {
    InsertResult out;
    out.pose = initial;
    out.reason = "invalid scan: " + why;
    return out;
  }
  return InsertPreprocessed(PreprocessScan(scan, options_.preprocessing), initial, insert);
}

InsertResult ContourMapper::InsertPreprocessed(PreprocessedScan scan, const Pose2& initial,
                                               const InsertOptions& insert) {
  InsertResult out;
  out.pose = initial;
  if (!std::isfinite(initial.x) || !std::isfinite(initial.y) || !std::isfinite(initial.theta)) {
    out.reason = "initial pose is not finite";
    return out;
  }
  if (scan.NumPoints() < options_.min_scan_points) {
    out.reason = "too few usable points (" + std::to_string(scan.NumPoints()) + " < " +
                 std::to_string(options_.min_scan_points) + ")";
    return out;
  }
  const bool first = scans_.empty();
  std::set<int> to_fit;
  if (!first) {
    PoseEstimationOptions pose_options = options_.pose;
    if (insert.initial_threshold > 0.0)
      pose_options.initial_threshold = std::max(insert.initial_threshold, pose_options.final_threshold);
    out.estimation = EstimatePose(scan, initial, map_, pose_options);
    out.pose = out.estimation.pose;
    const PoseEstimationResult& e = out.estimation;
    std::ostringstream why;
    if (e.fit.num_pieces < pose_options.min_pieces)
      why << "no overlap with the map: " << e.status;
    else if (e.fit.MatchedFraction() < options_.min_overlap_fraction)
      why << "too little overlap with the map (" << 100.0 * e.fit.MatchedFraction() << "% of points match)";
    else if (TranslationDistance(initial, e.pose) > options_.max_correction_translation ||
             HeadingDistance(initial, e.pose) > options_.max_correction_rotation)
      why << "correction too large (" << TranslationDistance(initial, e.pose) << " m, "
          << RadToDeg(HeadingDistance(initial, e.pose)) << " deg): initial estimate too far off";
    else if (std::sqrt(e.fit.MeanSquaredDistance()) > options_.max_rms_distance)
      why << "poor fit (RMS " << std::sqrt(e.fit.MeanSquaredDistance()) << " m)";
    if (!why.str().empty()) {
      out.reason = why.str();
      return out;
    }
    // What the scan sees through goes first (4.8.2): a wall that went is then no longer
    // there for the expansion to splice into, and its ends are free to be reconnected.
    if (options_.disappearance.enabled) {
      out.disappearance = RemoveDisappeared(scan, out.pose, map_, options_.disappearance);
      for (const int id : out.disappearance.changed) to_fit.insert(id);
    }
    // Contours the scan overlaps get refitted with its data.
    const ScanCorrespondence corr = CorrespondScan(scan, out.pose, map_, options_.fitting.correspondence_threshold);
    for (const ErrorPiece& p : corr.pieces) to_fit.insert(p.segment.contour);
  }
  out.expansion = ExpandMap(scan, out.pose, map_, options_.expansion);
  for (const int id : out.expansion.Touched()) to_fit.insert(id);

  scans_.push_back({std::move(scan), out.pose, first});
  out.scan_index = static_cast<int>(scans_.size()) - 1;
  std::vector<int> ids;
  for (const int id : to_fit)
    if (map_.Find(id)) ids.push_back(id);
  FitRegion region;
  region.lo = Eigen::Vector2d::Constant(1e300);
  region.hi = Eigen::Vector2d::Constant(-1e300);
  for (const PartialScan& p : scans_.back().scan.partial_scans)
    for (const Eigen::Vector2d& q : p.points) {
      const Eigen::Vector2d w = out.pose * q;
      region.lo = region.lo.cwiseMin(w);
      region.hi = region.hi.cwiseMax(w);
    }
  region.lo -= Eigen::Vector2d::Constant(options_.local_fit_margin);
  region.hi += Eigen::Vector2d::Constant(options_.local_fit_margin);
  if (options_.local_fit_radius > 0.0) {
    const Eigen::Vector2d sensor = out.pose * scans_.back().scan.sensor_position;
    region.lo = region.lo.cwiseMax(sensor - Eigen::Vector2d::Constant(options_.local_fit_radius));
    region.hi = region.hi.cwiseMin(sensor + Eigen::Vector2d::Constant(options_.local_fit_radius));
  }
  const FitRegion* fit_region = options_.local_fit_margin >= 0.0 ? &region : nullptr;
  if (options_.fit_scans > 0 && static_cast<int>(scans_.size()) > options_.fit_scans) {
    const std::vector<MappedScan> nearest = NearestScans(scans_, options_.fit_scans);
    out.fitting = FitContours(ids, nearest, map_, options_.fitting, fit_region);
  } else {
    out.fitting = FitContours(ids, scans_, map_, options_.fitting, fit_region);
  }
  if (options_.refine_after_each_scan) {
    Refine();
    out.pose = scans_.back().pose;
  }
  out.accepted = true;
  std::ostringstream summary;
  summary << (first ? "first scan (fixed)" : out.estimation.status) << "; created " << out.expansion.created.size()
          << ", extended " << out.expansion.extended.size() << ", connected " << out.expansion.connected.size()
          << ", spliced " << out.expansion.spliced.size() << " contours";
  if (out.disappearance.removed_length > 0.0) summary << "; removed " << out.disappearance.removed_length << " m seen through";
  out.reason = summary.str();
  return out;
}

ConcurrentRefinementResult ContourMapper::Refine() { return RefineConcurrently(scans_, map_, options_.refinement); }

ConcurrentRefinementResult ContourMapper::Refine(const ShouldStop& should_stop) {
  ConcurrentRefinementOptions options = options_.refinement;
  options.should_stop = should_stop;
  return RefineConcurrently(scans_, map_, options);
}

ConcurrentRefinementResult ContourMapper::RefineWith(const ConcurrentRefinementOptions& refinement) {
  return RefineConcurrently(scans_, map_, refinement);
}

}  // namespace minenav::mapper
