#include "mapper/concurrent_refinement.h"

#include <optional>
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

void DeclareOptions(OptionScope s, ConcurrentRefinementOptions& o) {
  DeclareOptions(s.Nested("loop_closure"), o.loop_closure);
  DeclareOptions(s.Nested("pose"), o.pose);
  DeclareOptions(s.Nested("fitting"), o.fitting);
  s.AddBool("remove_redundant", &o.remove_redundant,
            "remove redundant contours (a wall mapped twice) before every round: without it each "
            "end of a loop keeps matching its own copy and the loop never closes");
  DeclareOptions(s.Nested("redundant"), o.redundant);
  s.AddInt("max_rounds", &o.max_rounds,
           "alternating rounds (poses, then contours) at most; a round that raises the total error is undone and "
           "ends the refinement anyway [rounds]",
           1, 100000);
  s.AddDouble("min_relative_decrease", &o.min_relative_decrease, "1",
              "stop when a round lowers the total error by less than this fraction; 1e-3", 0.0, 1.0);
  s.AddDouble("evaluation_threshold", &o.evaluation_threshold, "m",
              "correspondence threshold of the total error that rounds are judged by; 0.2 m, as map "
              "expansion's",
              0.001, 100.0);
  // should_stop is a function a caller supplies (NodeRuntime::StopSignalled), not data.
}

double TotalError(const std::vector<MappedScan>& scans, const ContourMap& map, double threshold) {
  double total = 0.0;
  for (const MappedScan& s : scans) total += MeasureScanFit(s.scan, s.pose, map, threshold).error;
  return total;
}

namespace {

// TotalError, asking should_stop between scans (a whole map of thousands of scans takes
// seconds to measure). Empty when stopped.
std::optional<double> TotalErrorUnlessStopped(const std::vector<MappedScan>& scans, const ContourMap& map,
                                              double threshold, const ShouldStop& should_stop) {
  double total = 0.0;
  for (const MappedScan& s : scans) {
    if (should_stop && should_stop()) return std::nullopt;
    total += MeasureScanFit(s.scan, s.pose, map, threshold).error;
  }
  return total;
}

}  // namespace

ConcurrentRefinementResult RefineConcurrently(std::vector<MappedScan>& scans, ContourMap& map,
                                              const ConcurrentRefinementOptions& o) {
  ConcurrentRefinementResult out;
  // Once the caller's test said yes the answer is kept, so it is never asked again.
  bool said_yes = false;
  const ShouldStop should_stop = [&] { return said_yes = said_yes || (o.should_stop && o.should_stop()); };
  auto stop = [&](const std::string& why) {
    out.stopped = true;
    out.reason = "stopped " + why + ": " + std::to_string(out.rounds) + " rounds kept";
    return out;
  };
  const std::optional<double> initial = TotalErrorUnlessStopped(scans, map, o.evaluation_threshold, should_stop);
  if (!initial) return stop("before the first round");
  double previous = *initial;
  if (o.loop_closure.enabled) {
    std::vector<Pose2> saved_poses;
    for (const MappedScan& s : scans) saved_poses.push_back(s.pose);
    ContourMap saved_map = map;
    out.loop_closure = CloseLoops(scans, map, o.loop_closure, o.fitting, o.redundant, should_stop);
    if (out.loop_closure.stopped) return stop("in the pose-graph step");
    if (out.loop_closure.applied) {
      // Registrations can be wrong where scans see little (a corridor without features):
      // keep the closed loop only if the scans fit the refitted map better than before.
      const std::optional<double> closed = TotalErrorUnlessStopped(scans, map, o.evaluation_threshold, should_stop);
      if (!closed || *closed > previous) {
        for (size_t k = 0; k < scans.size(); ++k) scans[k].pose = saved_poses[k];
        map = std::move(saved_map);
        out.loop_closure.applied = false;
        if (!closed) {
          out.loop_closure.reason += "; undone: stopped";
          return stop("in the pose-graph step");
        }
        out.loop_closure.reason += "; undone: the total error rose";
      } else {
        previous = *closed;
      }
    }
  }
  out.total_error.push_back(previous);
  for (int round = 1; round <= o.max_rounds; ++round) {
    if (should_stop()) return stop("between rounds");
    std::vector<Pose2> saved_poses;
    for (const MappedScan& s : scans) saved_poses.push_back(s.pose);
    const ContourMap saved_map = map;
    auto undo = [&] {
      for (size_t k = 0; k < scans.size(); ++k) scans[k].pose = saved_poses[k];
      map = saved_map;
    };
    if (o.remove_redundant) RemoveRedundantContours(map, o.redundant);

    bool stopped = false;
    for (MappedScan& s : scans) {  // poses, contours fixed
      if (s.fixed) continue;
      if (should_stop()) {
        stopped = true;
        break;
      }
      const PoseEstimationResult r = EstimatePose(s.scan, s.pose, map, o.pose);
      if (r.fit.num_pieces >= o.pose.min_pieces) s.pose = r.pose;
    }
    if (stopped) {
      undo();
      return stop("in a round (undone)");
    }
    FitContours(map.Ids(), scans, map, o.fitting);  // contours, poses fixed

    const std::optional<double> current = TotalErrorUnlessStopped(scans, map, o.evaluation_threshold, should_stop);
    if (!current) {
      undo();
      return stop("in a round (undone)");
    }
    if (*current > previous) {
      undo();
      out.converged = true;
      out.reason = "total error rose: last round undone";
      return out;
    }
    out.rounds = round;
    out.total_error.push_back(*current);
    if (previous - *current <= o.min_relative_decrease * previous) {
      out.converged = true;
      out.reason = "total error stopped falling";
      return out;
    }
    previous = *current;
  }
  out.reason = "round limit";
  return out;
}

}  // namespace minenav::mapper
