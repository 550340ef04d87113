#pragma once
// Contour fitting (thesis 4.5): with the scan poses fixed, move the contour vertices to
// minimise the integral error (integral_error.h, EQ 4 for the gradient) of every scan
// against the contours. Each iteration:
//   1. remove degenerate (very short) segments, which make the gradient unstable and let
//      sensor noise into the contour, and spikes (vertices where the contour folds back);
//   2. compute correspondence of every nearby scan against the whole map (nearest wins),
//      keeping the pieces on the contours being fitted;
//   3. compute the gradient over all vertex coordinates;
//   4. line search along the descent direction (the largest vertex move bounded by the
//      correspondence threshold, EQ 5);
//   5. update the vertices.
// Five termination conditions: fewer than 2 segments, small gradient, small step (λ),
// small vertex change, iteration limit.
//
// Beyond the thesis: the descent direction may be preconditioned per vertex by the
// Gauss-Newton curvature of the metric (a 2x2 block per vertex, damped so directions the
// data do not constrain, like sliding along a straight wall, stay put). The thesis's plain
// gradient needs hundreds of iterations when vertices see very different amounts of data;
// the preconditioned direction converges in a few. Set precondition = false for the
// thesis's behaviour.

#include <string>
#include <vector>

#include "common/config.h"
#include "mapper/contour_map.h"
#include "mapper/mapped_scan.h"

namespace minenav::mapper {

struct ContourFittingOptions {
  // m; correspondence threshold between scans and the contours being fitted.
  double correspondence_threshold = 0.2;
  // m; segments shorter than this are merged away before each iteration.
  double min_segment_length = 0.1;
  // rad; vertices where the contour turns back by more than this are removed (beyond the
  // thesis: spikes left by noisy rough fits).
  double max_turn = 2.4;
  // Iteration limit (termination condition 5).
  int max_iterations = 30;
  // m; gradient small: max |∂F/∂vertex| / matched length below this.
  double gradient_tolerance = 1e-7;
  // m; line-search resolution (smallest vertex move searched).
  double step_resolution = 1e-4;
  // m; largest vertex move in an iteration below this ends the fit.
  double min_vertex_change = 1e-4;
  // Precondition the gradient by the per-vertex curvature (see above).
  bool precondition = true;
  // Damping of the per-vertex curvature, as a fraction of its trace.
  double damping = 0.05;
  // m; added to every vertex's curvature (≈ 3 % of a vertex seen along both its 0.5 m
  // segments), so a vertex that only a sliver of data touches does not take a huge
  // preconditioned step and wander off across iterations.
  double min_curvature = 0.02;
};

std::string ValidateOptions(const ContourFittingOptions& options);
// Declares every field of `o` under `scope` (unit, default, range, why): config keys and flags.
void DeclareOptions(OptionScope scope, ContourFittingOptions& o);

struct ContourFittingResult {
  bool converged = false;
  std::string reason;
  int iterations = 0;
  double error_before = 0.0;  // m^3, F over the fitted contours' pieces at the start
  double error_after = 0.0;   // m^3, same at the end (correspondence recomputed)
  int vertices_removed = 0;   // by degenerate-segment removal
  int num_pieces = 0;         // at the end
};

// An axis-aligned box in the world frame, metres.
struct FitRegion {
  Eigen::Vector2d lo = Eigen::Vector2d::Zero();
  Eigen::Vector2d hi = Eigen::Vector2d::Zero();
  bool Contains(const Eigen::Vector2d& p) const {
    return p.x() >= lo.x() && p.x() <= hi.x() && p.y() >= lo.y() && p.y() <= hi.y();
  }
};

// Fits the contours `ids` (missing ids are ignored) to `scans`. With a region, only the
// vertices inside it move and only scan data near it is used: the local refit after a scan
// is inserted costs what the scan's surroundings cost, not what the whole map costs.
ContourFittingResult FitContours(const std::vector<int>& ids, const std::vector<MappedScan>& scans, ContourMap& map,
                                 const ContourFittingOptions& options = {}, const FitRegion* region = nullptr);

}  // namespace minenav::mapper
