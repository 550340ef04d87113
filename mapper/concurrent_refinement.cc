#include "mapper/concurrent_refinement.h"

#include <sstream>

namespace minenav::mapper {

std::string ValidateOptions(const ConcurrentRefinementOptions& o) {
  if (std::string why = ValidateOptions(o.pose); !why.empty()) return "pose: " + why;
  if (std::string why = ValidateOptions(o.fitting); !why.empty()) return "fitting: " + why;
  if (std::string why = ValidateOptions(o.loop_closure); !why.empty()) return "loop_closure: " + why;
  std::ostringstream why;
  if (o.max_rounds < 1)
    why << "max_rounds must be >= 1, got " << o.max_rounds;
  else if (!(o.min_relative_decrease >= 0.0))
    why << "min_relative_decrease must be >= 0, got " << o.min_relative_decrease;
  else if (!(o.evaluation_threshold > 0.0))
    why << "evaluation_threshold must be > 0 m, got " << o.evaluation_threshold;
  return why.str();
}

double TotalError(const std::vector<MappedScan>& scans, const ContourMap& map, double threshold) {
  double total = 0.0;
  for (const MappedScan& s : scans) total += MeasureScanFit(s.scan, s.pose, map, threshold).error;
  return total;
}

ConcurrentRefinementResult RefineConcurrently(std::vector<MappedScan>& scans, ContourMap& map,
                                              const ConcurrentRefinementOptions& o) {
  ConcurrentRefinementResult out;
  double previous = TotalError(scans, map, o.evaluation_threshold);
  if (o.loop_closure.enabled) {
    std::vector<Pose2> saved_poses;
    for (const MappedScan& s : scans) saved_poses.push_back(s.pose);
    ContourMap saved_map = map;
    out.loop_closure = CloseLoops(scans, map, o.loop_closure, o.fitting, o.redundant);
    if (out.loop_closure.applied) {
      // Registrations can be wrong where scans see little (a corridor without features):
      // keep the closed loop only if the scans fit the refitted map better than before.
      const double closed = TotalError(scans, map, o.evaluation_threshold);
      if (closed > previous) {
        for (size_t k = 0; k < scans.size(); ++k) scans[k].pose = saved_poses[k];
        map = std::move(saved_map);
        out.loop_closure.applied = false;
        out.loop_closure.reason += "; undone: the total error rose";
      } else {
        previous = closed;
      }
    }
  }
  out.total_error.push_back(previous);
  for (int round = 1; round <= o.max_rounds; ++round) {
    std::vector<Pose2> saved_poses;
    for (const MappedScan& s : scans) saved_poses.push_back(s.pose);
    const ContourMap saved_map = map;
    if (o.remove_redundant) RemoveRedundantContours(map, o.redundant);

    for (MappedScan& s : scans) {  // poses, contours fixed
      if (s.fixed) continue;
      const PoseEstimationResult r = EstimatePose(s.scan, s.pose, map, o.pose);
      if (r.fit.num_pieces >= o.pose.min_pieces) s.pose = r.pose;
    }
    FitContours(map.Ids(), scans, map, o.fitting);  // contours, poses fixed

    const double current = TotalError(scans, map, o.evaluation_threshold);
    if (current > previous) {
      for (size_t k = 0; k < scans.size(); ++k) scans[k].pose = saved_poses[k];
      map = saved_map;
      out.converged = true;
      out.reason = "total error rose: last round undone";
      return out;
    }
    out.rounds = round;
    out.total_error.push_back(current);
    if (previous - current <= o.min_relative_decrease * previous) {
      out.converged = true;
      out.reason = "total error stopped falling";
      return out;
    }
    previous = current;
  }
  out.reason = "round limit";
  return out;
}

}  // namespace minenav::mapper
