#pragma once
// Map expansion (thesis 4.4): after a scan's pose is estimated, the parts of its partial
// scans that correspond to no contour are new. Each run of unmatched points becomes
//   - an extension of a contour's end, when the run follows points matched near that end
//     (4.4.2), or of a contour's start when it precedes points matched near that start;
//   - a connection of one contour's end to another's start (or to its own start, closing
//     it) when both hold (4.4.3);
//   - a new contour otherwise (4.4.1): the first and last points of the run and scan
//     points in between at least the nominal segment length apart (a rough fit that
//     contour fitting then improves).
// Runs that leave or reach a contour at an interior segment are the dynamic-world cases of
// 4.8.1 (splice, join): map_appearance.h classifies every run into the eight cases and
// applies the edit; with splice_interior off, interior neighbours count as none and the
// walk is the static expansion of 4.4 (such runs become new contours).

#include <array>
#include <vector>

#include "common/config.h"
#include "common/pose2.h"
#include "mapper/contour_map.h"
#include "mapper/scan_preprocessing.h"

namespace minenav::mapper {

struct MapExpansionOptions {
  // m; scan points farther than this from every contour are unmapped.
  double correspondence_threshold = 0.2;
  // m; vertex spacing of new contour pieces.
  double nominal_segment_length = 0.5;
  // Points; unmatched runs with fewer points are ignored (vertex wedges, noise).
  int min_new_points = 5;
  // m; unmatched runs shorter than this (along the scan) are ignored.
  double min_new_length = 0.3;
  // m; a run continues a contour's end (start) when the matched point next to it lies
  // this close to that end (start) vertex, or matched its last (first) segment.
  double end_snap_distance = 1.0;
  // Dynamic world (4.8.1): runs beside a match on a contour's interior segment are spliced
  // into that contour (an object placed against a wall). Off: they become new contours.
  bool splice_interior = true;
  // m; an interior anchor is used only for runs at least this long (along the run).
  double min_splice_length = 0.5;
  // A case-4 splice into one contour may bypass (leave as occluded) at most this many times
  // the length of the run from cut to cut; more means the run is not an object on the wall.
  double max_bypass_ratio = 1.5;
};

std::string ValidateOptions(const MapExpansionOptions& options);
// Declares every field of `o` under `scope` (unit, default, range, why): config keys and flags.
void DeclareOptions(OptionScope scope, MapExpansionOptions& o);

struct MapExpansionResult {
  std::vector<int> created;    // ids of new contours
  std::vector<int> extended;   // ids of contours extended at either end
  std::vector<int> connected;  // ids of contours that absorbed a connection (or closed)
  std::vector<int> spliced;    // ids of contours that a splice cut (4.8.1), remainders too
  std::array<int, 9> cases{};  // runs handled per case of map_appearance.h (0 = created)
  std::vector<int> Touched() const;  // all of the above that still exist, sorted, unique
};

MapExpansionResult ExpandMap(const PreprocessedScan& scan, const Pose2& world_T_vehicle, ContourMap& map,
                             const MapExpansionOptions& options = {});

}  // namespace minenav::mapper
