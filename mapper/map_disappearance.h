#pragma once
// Disappearance (thesis 4.8.2): removing the parts of contours that a new scan sees through.
//
// Each pair of adjacent scan points and the sensor form a triangle of coverage: the beam
// divergence fills the gap between neighbouring beams, so nothing stands inside the
// triangle (we widen it by half the divergence on each side). A contour segment is cut back
// where all of these hold (the thesis's three conditions, made explicit):
//   1. it crosses both sides of the triangle that meet at the sensor, and it lies between
//      the sensor and the points: where it crosses each side it is nearer to the sensor
//      than that side's scan point by more than the correspondence threshold (so neither
//      point corresponds to it — condition 2);
//   3. the view is not too glancing: both beams meet the segment at least min_view_angle
//      steeply (a wall the scanner looks along is not removed).
// The part of the segment between the two crossings is removed. Neighbouring readings in
// different partial scans (a range discontinuity) still bound a triangle, out to the nearer
// of the two ranges. Nothing is removed for age alone, and nothing the scan does not see.
//
// Beyond the thesis: a removed stretch shorter than min_removed_length along its contour is
// kept (fitting leaves contour ends a few cm past true corners, and rays past the corner
// would nibble them away scan after scan), and pieces left shorter than min_piece_length are
// dropped. Pose error: the scan's pose must be good (it is, after estimation); the
// threshold margin absorbs the rest.

#include <string>
#include <vector>

#include "common/config.h"
#include "common/pose2.h"
#include "mapper/contour_map.h"
#include "mapper/scan_preprocessing.h"

namespace minenav::mapper {

struct MapDisappearanceOptions {
  // Run the removal in the map-building cycle (ContourMapper); the function below always runs.
  bool enabled = true;
  // rad, full horizontal beam divergence (sensor_driver/ladar_model.h: Typhoon 3 mrad,
  // Cyclone 4 mrad).
  double beam_divergence = 0.003;
  // m; a segment must lie at least this far in front of the scan points to be seen through.
  double correspondence_threshold = 0.1;
  // rad; beams meeting a segment more glancingly than this remove nothing from it.
  double min_view_angle = 0.35;
  // m; removed stretches shorter than this (along the contour) are kept.
  double min_removed_length = 0.3;
  // m; pieces of a cut contour shorter than this are removed with the rest: what remains of
  // an object seen through all round, whose last bits were seen only glancingly or near its
  // corners (0.3 m left such bits of a parked machine in the bench).
  double min_piece_length = 0.6;
};

std::string ValidateOptions(const MapDisappearanceOptions& options);
// Declares every field of `o` under `scope` (unit, default, range, why): config keys and flags.
void DeclareOptions(OptionScope scope, MapDisappearanceOptions& o);

struct MapDisappearanceResult {
  double removed_length = 0.0;  // m of contour removed
  std::vector<int> changed;     // ids of contours that were cut and still exist (pieces too)
  int contours_removed = 0;     // contours removed entirely
};

// Removes from `map` what the scan at world_T_vehicle sees through.
MapDisappearanceResult RemoveDisappeared(const PreprocessedScan& scan, const Pose2& world_T_vehicle, ContourMap& map,
                                         const MapDisappearanceOptions& options = {});

}  // namespace minenav::mapper
