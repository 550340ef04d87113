#pragma once
// Loop closure by a pose graph (beyond thesis 4.7; thesis 7.2.2 "iconic front end"): the
// joint step that lets concurrent refinement close a drifted loop in one go instead of
// passing the correction around the loop one scan per round.
//   1. Pairs of scans whose current sensor positions are within max_pair_distance (a few
//      nearest recent scans and a few nearest loop candidates per scan) are registered directly, scan against scan: the points of the later scan against the raw
//      polylines of the earlier one (the iconic matcher of thesis 3.3, pose_estimator/),
//      from their current relative pose. A registration that converges with enough overlap
//      and a small residual becomes an edge with the matcher's covariance.
//   2. Consecutive scans (in insertion order) are also tied by a weak prior on their current
//      relative pose, so the graph stays connected where registration fails.
//   3. The pose graph (pose_graph.h) is optimised; registration edges that still disagree
//      with the solution by more than a gate are dropped as false matches and it is
//      optimised again.
//   4. If the poses moved, the contours are carried along: each vertex moves with the
//      corrections of the scans that see it (weighted by how many of their points match its
//      segments), unobserved vertices are interpolated along their contour. Copies of a
//      wall made at both ends of the loop then lie on top of each other; redundant copies
//      are removed and every contour is refitted to all scans at their new poses.
// Concurrent refinement (concurrent_refinement.h) runs this first, then polishes poses and
// contours against each other. It relies only on the scans, not on the contours, so it
// works however far the map has been bent by drift, as long as a loop's two ends fall within
// the registration's basin (about initial_threshold; the iconic matcher converges from 1 m
// and 10° on the synthetic mine). A caller with long loops and large drift runs it
// periodically (ContourMapper::Refine every few scans) so that the drift accumulated since
// the last closure stays inside that basin.

#include <functional>
#include <string>
#include <vector>

#include "common/config.h"
#include "mapper/contour_fitting.h"
#include "mapper/contour_map.h"
#include "mapper/mapped_scan.h"
#include "mapper/pose_graph.h"
#include "mapper/redundant_contours.h"

namespace minenav::mapper {

// A caller's "should this computation stop now?" test (a stop request, a deadline; the
// library knows nothing of signals). Long loops ask it between iterations and, once it says
// yes, return soon with their inputs left consistent. It must keep saying yes once it has.
// Empty: never stop.
using ShouldStop = std::function<bool()>;

// Graph options for loop closure: Huber beyond 3σ, so a false registration that slipped
// through the checks bends the solution little before the gate drops it.
inline PoseGraphOptions DefaultLoopClosureGraphOptions() {
  PoseGraphOptions o;
  o.huber_scale = 3.0;
  o.max_iterations = 100;  // reweighting slows convergence
  return o;
}

struct LoopClosureOptions {
  // Run the pose-graph step at the start of concurrent refinement.
  bool enabled = true;
  // m; pairs of scans whose sensors are farther apart than this (at the current poses) are
  // not registered.
  double max_pair_distance = 20.0;
  // Each scan is registered against at most max_recent_pairs nearest earlier scans and
  // max_loop_pairs nearest scans at least loop_index_gap scans earlier (loop candidates), so
  // the cost grows with the number of scans, not with its square, where many scans crowd
  // one place (a robot scanning at 5-10 Hz).
  int max_recent_pairs = 4;
  int max_loop_pairs = 4;
  int loop_index_gap = 8;
  // m; first correspondence threshold of a registration: how far the current relative pose
  // of two scans may be off (also the reach of each scan's lookup table).
  double initial_threshold = 1.0;
  // m; the registration runs in stages whose threshold floor starts here and is multiplied
  // by coarse_factor down to min_threshold, so points of a crib or a corner that are still
  // this far off keep pulling (a single pass drops them as outliers at once).
  double coarse_threshold = 0.8;
  double coarse_factor = 0.6;
  // m; floor of the registration's shrinking threshold (≈ 3σ of two noisy raw scans).
  double min_threshold = 0.15;
  // Fraction of the registered scan's points that must match the other within the final
  // threshold for the registration to count.
  double min_overlap = 0.25;
  // m; RMS residual of an accepted registration at most.
  double max_residual = 0.06;
  // Every k-th point of the registered scan is used (1 = all).
  int point_stride = 2;
  // m, rad; floor added to each registration's covariance (its σ² alone is optimistic:
  // raw polylines carry correlated range noise).
  double covariance_floor_translation = 0.003;
  double covariance_floor_rotation = 0.0002;
  // m, rad; σ of the prior tying consecutive scans to their current relative pose.
  double prior_sigma_translation = 0.2;
  double prior_sigma_rotation = 0.02;
  // m, rad; after optimisation a registration edge off by more than these is dropped.
  double gate_translation = 0.05;
  double gate_rotation = 0.005;
  // Optimise / drop / optimise passes at most.
  int max_gate_passes = 4;
  // m, rad; the graph's solution is applied only if some kept registration disagrees with
  // the current poses by more than one of these: a loop to close. Otherwise the poses
  // already agree with the scans within the registrations' own accuracy (≈ 1-2 cm on Typhoon
  // scans, worse than the contour estimate's), and the map is left for the contour rounds.
  double loop_translation = 0.1;
  double loop_rotation = 0.012;
  // m; a scan point this close to a contour segment (before the correction) counts as
  // seeing that segment's vertices when the contours are carried along.
  double observation_threshold = 0.3;
  // rad; a registration that turned the pair by more than this from its current relative
  // pose (or moved it by more than initial_threshold) left its basin: rejected (in a
  // room-and-pillar mine one entry looks like the next).
  double max_rotation_change = 0.1;
  PoseGraphOptions graph = DefaultLoopClosureGraphOptions();
};

std::string ValidateOptions(const LoopClosureOptions& options);
// Declares every field of `o` under `scope` (unit, default, range, why): config keys and flags.
void DeclareOptions(OptionScope scope, LoopClosureOptions& o);

// One registration of scan `to` against scan `from`.
struct ScanPairEdge {
  PoseGraphEdge edge;
  double residual = 0.0;  // m, RMS at the end
  double overlap = 0.0;   // fraction of points matched
};

// Registers every pair of scans within options.max_pair_distance (current poses) and returns
// the accepted registrations. *pairs_tried (if given) counts the registrations attempted.
// should_stop is asked before each registration: once it says yes, the edges so far return.
std::vector<ScanPairEdge> RegisterScanPairs(const std::vector<MappedScan>& scans, const LoopClosureOptions& options,
                                            int* pairs_tried = nullptr, const ShouldStop& should_stop = {});

// Moves every contour vertex with the scans that observe it from old_poses to the scans'
// current poses (see 4. above).
void CarryContoursWithScans(const std::vector<MappedScan>& scans, const std::vector<Pose2>& old_poses,
                            ContourMap& map, double observation_threshold);

struct LoopClosureResult {
  bool applied = false;  // poses and contours were changed
  bool stopped = false;  // should_stop said yes: nothing was changed
  std::string reason;
  int pairs_tried = 0;
  int edges = 0;           // registration edges kept
  int edges_rejected = 0;  // dropped by the gate
  double max_correction_translation = 0.0;  // m, largest pose change of the graph solution
  double max_correction_rotation = 0.0;     // rad
  double max_disagreement_translation = 0.0;  // m, largest kept registration vs current poses
  double max_disagreement_rotation = 0.0;     // rad
  PoseGraphResult graph;
};

// Steps 1-4 above on the scans and map; `fitting` and `redundant` are used for the refit.
// should_stop is asked between registrations and between the graph's passes; stopped, the
// scans and the map are left as they were (the refit of step 4, once begun, completes).
LoopClosureResult CloseLoops(std::vector<MappedScan>& scans, ContourMap& map, const LoopClosureOptions& options,
                             const ContourFittingOptions& fitting, const RedundantContourOptions& redundant,
                             const ShouldStop& should_stop = {});

}  // namespace minenav::mapper
