#pragma once
// ContourMapper: the incremental map-building cycle of thesis 4.1.2 over the pieces of this
// library. InsertScan:
//   1. preprocess the scan (scan_preprocessing.h);
//   2. estimate its pose against the contours from the initial pose given (4.3);
//   3. refuse it if it does not fit (too few points, too little overlap, a correction larger
//      than the initial error can be, a poor final fit): the map is left untouched;
//   4. remove what the scan sees through (4.8.2, disappearance.enabled), then expand the
//      map where the scan sees new walls, splicing objects into walls (4.4, 4.8.1);
//   5. fit the contours the scan created or overlapped (4.5);
//   6. optionally refine every pose and contour concurrently (4.7).
// The first scan anchors the frame: it is kept at its given pose and never moved.
//
// Front-end seam (7.2.2): the initial pose may come from odometry or from a front end such
// as the iconic estimator; pass InsertOptions::initial_threshold to tell the contour
// estimator how far off that pose may be (a refined front-end pose needs a small one).

#include <string>
#include <vector>

#include "common/config.h"
#include "common/scan.h"
#include "mapper/concurrent_refinement.h"
#include "mapper/contour_fitting.h"
#include "mapper/contour_map.h"
#include "mapper/map_disappearance.h"
#include "mapper/map_expansion.h"
#include "mapper/mapped_scan.h"
#include "mapper/pose_estimation.h"
#include "mapper/scan_preprocessing.h"

namespace minenav::mapper {

struct ContourMapperOptions {
  ScanPreprocessingOptions preprocessing;
  PoseEstimationOptions pose;
  MapExpansionOptions expansion;
  MapDisappearanceOptions disappearance;
  ContourFittingOptions fitting;
  ConcurrentRefinementOptions refinement;
  // m; cell size of the contour map's segment grid.
  double grid_cell_size = 2.0;
  // Points; scans with fewer usable points are refused.
  int min_scan_points = 50;
  // Fraction of the scan's points that must correspond to the map after pose estimation.
  double min_overlap_fraction = 0.15;
  // m, rad; a correction larger than this from the initial pose is refused (it means the
  // estimate locked onto the wrong walls).
  double max_correction_translation = 2.0;
  double max_correction_rotation = 0.35;
  // m; refuse a scan whose RMS distance to the contours it matched stays above this.
  double max_rms_distance = 0.06;
  // m; after an insert only contour vertices within the new scan's bounding box grown by
  // this margin are refitted (the rest of the map keeps its shape). < 0: refit whole contours.
  double local_fit_margin = 1.0;
  // Scans an insert's refit uses: the new one and the ones taken nearest to it (sensor
  // positions), at most this many; 0 = every mapped scan (the thesis). All scans make an
  // insert's cost grow with the map (a 360-degree scan's box covers most of a section, so
  // the local region does not bound it); a bound keeps a live mapper's inserts flat.
  int fit_scans = 0;
  // m; and only vertices within this distance of the new scan's sensor (along x and y): a far
  // wall the scan sees sparsely keeps the shape the scans near it gave it. 0 = the box alone.
  double local_fit_radius = 0.0;
  // Run concurrent refinement after every accepted scan (slow; thesis 4.7 suggests it for
  // maximum accuracy). Otherwise call Refine() when wanted.
  bool refine_after_each_scan = false;
};

std::string ValidateOptions(const ContourMapperOptions& options);

// The last of `scans` and the ones whose sensor stood nearest to it, `count` in all (all of
// them when there are fewer), in their original order: the data an insert's refit uses.
std::vector<MappedScan> NearestScans(const std::vector<MappedScan>& scans, int count);
// Declares every field of `o` under `scope` (unit, default, range, why): config keys and flags.
void DeclareOptions(OptionScope scope, ContourMapperOptions& o);

struct InsertOptions {
  // m; overrides pose.initial_threshold for this scan (0 = use the option's value).
  double initial_threshold = 0.0;
};

struct InsertResult {
  bool accepted = false;
  std::string reason;  // why refused, or a summary when accepted
  int scan_index = -1;  // index in scans() when accepted
  Pose2 pose;           // the estimate (the initial pose when refused before estimation)
  PoseEstimationResult estimation;
  MapDisappearanceResult disappearance;
  MapExpansionResult expansion;
  ContourFittingResult fitting;
};

class ContourMapper {
 public:
  explicit ContourMapper(ContourMapperOptions options = {});

  const ContourMapperOptions& options() const { return options_; }
  const ContourMap& map() const { return map_; }
  const std::vector<MappedScan>& scans() const { return scans_; }

  InsertResult InsertScan(const LadarScan& scan, const Pose2& initial_world_T_vehicle,
                          const InsertOptions& insert = {});
  InsertResult InsertPreprocessed(PreprocessedScan scan, const Pose2& initial_world_T_vehicle,
                                  const InsertOptions& insert = {});

  // Concurrent refinement of every pose and contour (4.7), stopped early when
  // options().refinement.should_stop says so.
  ConcurrentRefinementResult Refine();
  // The same with another stop test in place of the options' (empty: run to the end).
  ConcurrentRefinementResult Refine(const ShouldStop& should_stop);
  // The same with other refinement options in place of options().refinement (a final
  // refinement of its own number of rounds).
  ConcurrentRefinementResult RefineWith(const ConcurrentRefinementOptions& refinement);

  // Replaces the map (e.g. loaded from a file); scans are kept.
  void SetMap(ContourMap map) { map_ = std::move(map); }
  // Replaces the whole state (checkpoint restore, map_checkpoint.h).
  void RestoreState(ContourMap map, std::vector<MappedScan> scans) {
    map_ = std::move(map);
    scans_ = std::move(scans);
  }

 private:
  ContourMapperOptions options_;
  ContourMap map_;
  std::vector<MappedScan> scans_;
};

}  // namespace minenav::mapper
