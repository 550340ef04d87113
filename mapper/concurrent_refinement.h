#pragma once
// Concurrent refinement (thesis 4.7, the thesis's main result): alternately refine every
// scan pose with the contours fixed (pose_estimation.h) and every contour with the poses
// fixed (contour_fitting.h) until the total error stops falling. Scans and contours pull
// each other together; where scans see the same walls from both ends of a loop, the loop
// closes. Callable after every scan or on demand. The first (fixed) scan anchors the frame.
// A round that raises the total error is undone and ends the refinement.
//
// Beyond the thesis: alternating alone passes a loop's closing correction around the loop
// about one scan per round (the thesis ran 9 scans overnight; a 16-scan loop with 0.5 m of
// drift was still 0.3 m off after 20 rounds). So refinement first runs a joint step over all
// poses, a pose graph of scan-to-scan registrations (loop_closure.h), carries the contours
// along with their scans and refits them; the alternating rounds then polish the result.

#include <string>
#include <vector>

#include "common/config.h"
#include "mapper/contour_fitting.h"
#include "mapper/contour_map.h"
#include "mapper/loop_closure.h"
#include "mapper/mapped_scan.h"
#include "mapper/pose_estimation.h"
#include "mapper/redundant_contours.h"

namespace minenav::mapper {

// Pose options for refinement: poses are already close, so the threshold starts small.
inline PoseEstimationOptions DefaultRefinementPoseOptions() {
  PoseEstimationOptions o;
  o.initial_threshold = 0.5;  // m
  o.final_threshold = 0.1;    // m
  o.min_pieces = 10;
  return o;
}

struct ConcurrentRefinementOptions {
  // The pose-graph step run before the rounds (loop_closure.enabled = false: the thesis's
  // alternation alone).
  LoopClosureOptions loop_closure;
  // Pose refinement with the contours fixed.
  PoseEstimationOptions pose = DefaultRefinementPoseOptions();
  ContourFittingOptions fitting;
  // Redundant contours (a wall mapped twice) are removed before every round, so scans at
  // both ends of a loop match the same contour.
  bool remove_redundant = true;
  RedundantContourOptions redundant;
  // Rounds (poses then contours) at most.
  int max_rounds = 20;
  // Stop when a round lowers the total error by less than this fraction.
  double min_relative_decrease = 1e-3;
  // m; correspondence threshold used to measure the total error.
  double evaluation_threshold = 0.2;
  // Asked between scans, rounds and registrations (loop_closure.h ShouldStop): once it says
  // yes the refinement returns within one step (one scan's pose, one registration, one
  // whole-map fit), the round under way undone. Empty (default): run to the end.
  ShouldStop should_stop;
};

std::string ValidateOptions(const ConcurrentRefinementOptions& options);
// Declares every field of `o` under `scope` (unit, default, range, why): config keys and flags.
void DeclareOptions(OptionScope scope, ConcurrentRefinementOptions& o);

// Σ over scans of the integral error against the map under `threshold`.
double TotalError(const std::vector<MappedScan>& scans, const ContourMap& map, double threshold);

struct ConcurrentRefinementResult {
  bool converged = false;
  bool stopped = false;  // should_stop said yes: poses and map as after the last kept round
  std::string reason;
  int rounds = 0;                   // rounds kept
  std::vector<double> total_error;  // m^3, before the first round and after each kept round
  LoopClosureResult loop_closure;   // the pose-graph step (reason "" if disabled)
};

ConcurrentRefinementResult RefineConcurrently(std::vector<MappedScan>& scans, ContourMap& map,
                                              const ConcurrentRefinementOptions& options = {});

}  // namespace minenav::mapper
