#pragma once
// Appearance (thesis 4.8.1): contour editing where a scan sees something the map does not
// hold. Map expansion (map_expansion.h) walks each partial scan point by point after pose
// estimation; every maximal run of points without correspondence is bounded by the matched
// points next to it (or by the partial scan's start or end). What those neighbours matched
// decides the case:
//
//   left of the run (before it)   right of the run (after it)   case, action
//   nothing                        first segment of a contour    1  extend the contour's start
//   nothing                        interior segment              2  join: splice into the segment
//   last segment of a contour      first segment of a contour    3  connect the two (or close one)
//   interior segment               interior segment              4  splice into both
//   last segment of a contour      interior segment              5  extend the end, splice
//   interior segment               first segment of a contour    6  splice, extend the start
//   last segment of a contour      nothing                       7  extend the end
//   interior segment               nothing                       8  splice, then extend
//   nothing                        nothing                       0  create a new contour (4.4.1)
//
// "First/last segment" also covers a match within end_snap_distance of the open end.
// Splicing (contour_map.h): the contour is cut at the foot of the matched point and the run
// is attached to the cut, so an object placed against a mapped wall becomes one contour with
// the wall (the sensor cannot tell them apart). The wall between the two cuts of case 4 is
// now occluded: it stays in the map as a contour of its own, untouched (no evidence that it
// went; the thesis's philosophy).
//
// A static world is the special case without interior anchors (options.splice_interior =
// false): cases 2, 4, 5, 6 and 8 then degrade to 0, 1 or 7, which is exactly map expansion
// of 4.4. Short runs beside an interior match come from corners and noise, not from new
// objects, so interior anchors need a run of at least min_splice_length; a case-4 splice
// into one contour whose bypassed stretch is much longer than the run (the scan would cut
// away more wall than the object could hide) is refused the same way.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mapper/contour_map.h"
#include "mapper/correspondence.h"

namespace minenav::mapper {

struct MapExpansionOptions;  // map_expansion.h

// What one neighbour of an unmatched run matched.
struct RunAnchor {
  enum class Kind { kNone, kContourEnd, kContourStart, kInterior };
  Kind kind = Kind::kNone;
  int contour = -1;
  int segment = -1;
  // kContourEnd / kContourStart: the contour's end / start vertex; kInterior: the foot of
  // the matched point on the segment (where the contour is cut).
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
};

// The neighbour before a run (the run continues the contour forward from it) and after it.
RunAnchor LeftAnchor(const ContourMap& map, const PointMatch& match, const Eigen::Vector2d& point,
                     double end_snap_distance);
RunAnchor RightAnchor(const ContourMap& map, const PointMatch& match, const Eigen::Vector2d& point,
                      double end_snap_distance);

// The case number of the table above (0..8).
int AppearanceCase(const RunAnchor& left, const RunAnchor& right);

struct AppearanceEdit {
  int case_number = 0;        // the case applied (after any downgrade)
  int contour = -1;           // the contour that now holds the run (-1: nothing done)
  std::vector<int> spliced;   // contours cut by a splice (left alone remainders included)
  bool extended = false;      // an existing contour's end or start grew
  bool connected = false;     // two ends were joined, or a contour closed
};

// Applies the edit for one unmatched run (world frame, scan order) between `left` and
// `right`. Interior anchors are downgraded to kNone when options.splice_interior is off, or
// the run is shorter than options.min_splice_length, or the splice would bypass too much.
AppearanceEdit ApplyAppearance(ContourMap& map, const std::vector<Eigen::Vector2d>& run, RunAnchor left,
                               RunAnchor right, const MapExpansionOptions& options);

}  // namespace minenav::mapper
