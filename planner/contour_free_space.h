#pragma once
// The walls the path planner plans against on a contour map (thesis 4.1.1, 6.2.2), and the
// space the ladar has seen to be free.
//
// A contour's points run with the free space it was sensed from on the LEFT
// (mapper/contour.h). An open contour ends where the ladar stopped seeing a wall: out of
// range, in a shadow, or at an opening into space no scan has seen. A path must stay in seen
// free space, so unless a request allows unknown space (exploration) every open end is
// closed by a FRONTIER: a segment from a contour's end to the start of the contour that
// continues the boundary of the free space, oriented like the contours (free space on its
// left). The region the vehicle is in is then bounded by seen walls and frontiers.
//
// Which start continues an end (MakeContourFreeSpace): walking along contour A to its end e,
// the boundary of the free space goes on, through space not seen, to the start s of some
// contour B. The candidates s for e are the starts of the open contours (A's own included)
// such that
//   * the frontier e -> s crosses no wall (it touches walls only at e and s), and
//   * free space is on the consistent side: the free space left of A at e and left of B at s
//     is left of the frontier too, i.e. the boundary does not fold back on itself there (a
//     left turn of more than 180 deg - min_interior_angle from A's last segment onto the
//     frontier, or from the frontier onto B's first segment, would leave a sliver of interior
//     angle under min_interior_angle, the mark of a start that belongs to a wall seen from
//     the other side). Right turns are all consistent: behind a pillar's edge the boundary
//     turns right into the shadow ray (a reflex corner of the free space).
//   * looking from the frontier into the space it bounds (to its left, from a quarter, half
//     and three quarters of its length) the first wall is seen from its free side: a frontier
//     drawn straight along a wall across a pillar's shadow sees the back of the pillar's face
//     and is not drawn while a start that follows the shadow ray is to be had.
// Each end considers the 24 starts nearest to it. Ends and starts are then paired nearest
// first (each used once, no frontier crossing another), an end left over is joined to its
// nearest candidate start even if that start is taken, a start left over from its nearest
// candidate end; ends and starts that no candidate passing every test reaches get the nearest
// that passes the first two. What is still open is counted (`unclosed_ends`): there the walls
// alone (and the map's bounding box, which the planner adds) bound the region.
//
// Known free space (KnownFreeSpace): a point is in it when, looking along each of a few rays
// from it, the first wall or frontier hit has the point on its free (left) side, for most of
// the rays. Inside the boundary every ray meets it from the free side; in a pillar, behind a
// frontier or outside the map the first hit is seen from its back or nothing is hit.
//
// Plain C++: no LCM, clock or I/O.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "common/segment_index.h"
#include "mapper/contour.h"

namespace minenav {

class OptionScope;

struct FreeSpaceOptions {
  // deg: a frontier that leaves less interior angle than this between itself and the contour
  // it joins (the boundary folds back) does not continue that contour. Default 10.
  double min_interior_angle_deg = 10.0;
  // Rays cast by KnownFreeSpace::Contains; the point is free when more than half see a free
  // side first. Default 8.
  int probe_rays = 8;
  // m: rays of KnownFreeSpace::Contains look this far; nothing hit = unknown. Default 200.
  double probe_range = 200.0;
};

// "" when usable, else one line naming the option.
std::string ValidateOptions(const FreeSpaceOptions& options);
// min_interior_angle_deg, probe_rays, probe_range.
void DeclareOptions(OptionScope scope, FreeSpaceOptions& options);

struct ContourFreeSpace {
  std::vector<Segment> walls;      // every segment of every contour, in its contour's direction
  std::vector<Segment> frontiers;  // end of one open contour -> start of the next (free space on the left)
  int open_contours = 0;           // contours with an end to close (open, at least 2 points)
  int unclosed_ends = 0;           // ends and starts no frontier could reach

  // What the planner plans against: the walls, and the frontiers unless unknown space is allowed.
  std::vector<Segment> Boundary(bool allow_unknown) const;
};

ContourFreeSpace MakeContourFreeSpace(const std::vector<mapper::Contour>& contours,
                                      const FreeSpaceOptions& options = {});

// The frontiers that stay `margin` or more from `polygon` (m, map frame: a vehicle's
// footprint). The vehicle stands where the ladar has looked from, so a frontier through it is
// not the edge of what the ladar saw (MakeContourFreeSpace's pairing of contour ends can draw
// one along a wall across a crossing). `dropped` (may be null) counts the others.
std::vector<Segment> FrontiersAwayFrom(const std::vector<Segment>& frontiers,
                                       const std::vector<Eigen::Vector2d>& polygon, double margin,
                                       int* dropped = nullptr);

// Point queries against the walls and frontiers of one ContourFreeSpace.
class KnownFreeSpace {
 public:
  KnownFreeSpace(const ContourFreeSpace& space, const FreeSpaceOptions& options = {});
  // Has the ladar seen p (m, map frame) to be free?
  bool Contains(const Eigen::Vector2d& p) const;

 private:
  FreeSpaceOptions options_;
  std::unique_ptr<StaticSegmentIndex> index_;  // null when there is no boundary at all
};

}  // namespace minenav
