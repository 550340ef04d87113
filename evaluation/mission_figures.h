#pragma once
// The figures of a mission report, each a small function of plain inputs (tested one by
// one against hand-made cases with known answers; evaluation/README.md "Mission report"
// says what each means):
//   explored area   a grid over the section: which cell centres are truly free (parity of
//                   the crossings with the true walls, which form closed loops) and which the
//                   map shows free (a predicate: KnownFreeSpace::Contains of the contour map);
//   pose error      every estimate against the truth interpolated at its utime;
//   cut depth       rays along the direction of advance across the inner part of a face:
//                   how much farther the face is after the cut;
//   planning times  the path planner's search times parsed from its status lines;
//   distributions   count, mean, median, p95 and max of a list of values.
// Plain C++: no LCM, clock or I/O.

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/file_io.h"
#include "common/geometry.h"
#include "common/pose2.h"
#include "common/segment_index.h"

namespace minenav {

// ---------------------------------------------------------------------------- distributions

struct Distribution {
  int count = 0;
  double mean = 0.0, median = 0.0, p95 = 0.0, max = 0.0;  // 0 when count is 0
};
// p95 is the nearest-rank percentile (the smallest value with at least 95 % of the values at
// or below it); the median of an even count is the mean of the two middle values.
Distribution Summarize(std::vector<double> values);

// ----------------------------------------------------------------------------- explored area

// Is p inside the free space of a world made of closed wall loops (inside the outer boundary,
// outside every pillar)? The parity of the crossings of the ray from p towards +x with the
// walls, a wall counted when its ends lie on either side of the ray's line (half-open at
// vertices, so a ray through a vertex of a loop counts that loop once).
bool FreeByParity(const std::vector<Segment>& walls, const Eigen::Vector2d& p);

// Cells of a grid over the section: truly free (centre free by parity in the true world) and
// known free (the map's predicate at the centre).
struct AreaGrid {
  GridFrame frame;                  // cells of `cell` m over the box given
  std::vector<uint8_t> truly_free;  // by frame.Index(ix, iy)
  std::vector<uint8_t> known_free;
};
// The grid covering [lo, hi]; the truth by a scan line per row (the same answer as
// FreeByParity at every centre), the map's predicate called once per cell.
AreaGrid MakeAreaGrid(const std::vector<Segment>& true_walls,
                      const std::function<bool(const Eigen::Vector2d&)>& known_free, const Eigen::Vector2d& lo,
                      const Eigen::Vector2d& hi, double cell);

struct AreaFigures {
  double cell_m = 0.0;
  double true_free_m2 = 0.0;       // cells truly free
  double known_free_m2 = 0.0;      // cells the map shows free
  double explored_m2 = 0.0;        // both
  double falsely_free_m2 = 0.0;    // the map shows free, the truth is wall or outside
  double explored_fraction = 0.0;  // explored / true free (0 when nothing is free)
};
AreaFigures MeasureArea(const AreaGrid& grid);

// Rectangles (one per run of cells along a row) covering the cells where both flags have the
// wanted values, for drawing.
std::vector<std::vector<Eigen::Vector2d>> CellRuns(const AreaGrid& grid, bool truly_free, bool known_free);

// ------------------------------------------------------------------------------- pose error

struct PoseErrorFigures {
  int compared = 0;    // poses with a truth at their utime
  int unmatched = 0;   // poses without one (no truth within max_gap_us)
  double mean_m = 0.0, rms_m = 0.0, max_m = 0.0;  // position error
  double mean_heading_rad = 0.0, max_heading_rad = 0.0;
  int64_t worst_utime = 0;  // where the position error is largest
};
// `truth` sorted by utime; each pose is compared with the truth at its utime (PoseAtTime:
// exact, or interpolated between readings at most 2 max_gap_us apart).
PoseErrorFigures ComparePoses(const std::vector<StampedPose>& poses, const std::vector<StampedPose>& truth,
                              int64_t max_gap_us);
// The track moved rigidly so that its first pose with a truth lands on that truth: dead
// reckoning runs in its own frame, fixed where it started. Unchanged when no pose has one.
std::vector<StampedPose> AlignToTruthAtStart(const std::vector<StampedPose>& track,
                                             const std::vector<StampedPose>& truth, int64_t max_gap_us);

// -------------------------------------------------------------------------------- cut depth

struct CutDepthOptions {
  double inner_from = 0.1;  // fraction of the face's length where the rays start
  double inner_to = 0.9;    // and end
  int rays = 17;            // rays across [inner_from, inner_to] (>= 1)
  double back_off = 1.0;    // m: the rays start this far behind the face, in the free space
  double reach = 10.0;      // m past the face a ray looks for the new face
};

struct DepthFigures {
  int rays = 0;
  int hits = 0;  // rays that hit both before and after
  double median = 0.0, min = 0.0, max = 0.0;  // m, 0 when no hits
};

// How far the face moved along `advance` (unit direction of advance) between two sets of
// walls: per ray, hit distance after minus hit distance before; rays from points of the face
// at inner_from..inner_to of its length, `back_off` behind it.
DepthFigures MeasureFaceAdvance(const Segment& face, const Eigen::Vector2d& advance, const StaticSegmentIndex& before,
                                const StaticSegmentIndex& after, const CutDepthOptions& options = {});

// ---------------------------------------------------------------------------- planning times

// What one status line of the path planner says about its search ("[replanned: ...: ]ok:
// 26.00 m, 3 pieces, 0 reversals, 1200 expansions, 3.0 ms on map version 1").
struct PlannerSearch {
  double length_m = 0.0;
  double ms = 0.0;
  int64_t map_version = 0;
  bool replanned = false;
};
// nullopt for any line that is not such an answer (refusals, garbage, cut lines).
std::optional<PlannerSearch> ParsePlannerStatus(const std::string& status);

}  // namespace minenav
