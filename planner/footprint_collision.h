#pragma once
// Does the vehicle's polygon at a pose come within `margin` of a wall? Decided in three
// steps (the clearance field first, exact geometry only where it cannot tell):
//   free      every disc of a cover of the polygon (a chain of discs along its long axis,
//             the Hybrid-A* / Nav2 Smac trick) has a centre whose clearance is surely above
//             the disc's radius + margin (ClearanceField::LowerBound): no wall comes within
//             margin of any point of the discs, so none of the polygon;
//   blocked   the pose's origin, the inscribed radius from the polygon's boundary, has a
//             clearance surely below that + margin (ClearanceField::UpperBound): a wall is
//             inside the polygon or within margin of its boundary (only the origin: a sweep's
//             first colliding pose is within a step of contact, where no inside point can
//             tell; the disc centres, asked too until the sixth speed round, decided 0.1 % of
//             the 6 m slab cut's checks at nine lookups each of the 64 % the exact test took);
//   otherwise the exact polygon-against-segment test against the walls near the pose
//             (common/segment_index.h): a wall end inside the polygon, or a wall within margin
//             of an edge, is a collision; when free, the least distance measured less the
//             margin is the spare (capped), so the sweeps skip poses near walls too. A
//             rectangle (the polygon is its own box) takes one box-to-segment distance per
//             wall instead of every edge: 1.6-1.8x faster (bench/footprint_collision_bench).
// Both field decisions are implied by the exact test's answer, so the field changes the time
// a check takes, never its result (planner_test checks that against brute force).

#include <cmath>
#include <cstdint>
#include <vector>

#include "common/pose2.h"
#include "common/segment_index.h"
#include "planner/clearance_field.h"
#include "planner/footprint.h"

namespace minenav {

// How the poses tested so far were decided.
struct CollisionCounters {
  int64_t free_by_field = 0;
  int64_t blocked_by_field = 0;
  int64_t exact_tests = 0;
};

// Distance between two segments (0 when they meet).
double SegmentToSegmentDistance(const Segment& s, const Segment& t);

// A disc in the vehicle frame (m).
struct Disc {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius = 0.0;
};

// `count` discs that together hold the polygon: its bounding box cut across its longer side
// into `count` equal slices, each slice's disc about the slice's centre with half its
// diagonal as radius (a 10 x 3.3 m rectangle, 8 discs: radius 1.76 m, 0.11 m more than the
// half width). count >= 1.
std::vector<Disc> DiscCover(const Footprint& footprint, int count);

// The result of one check: collides, or free with `spare` m to spare: every point of the
// polygon may move up to `spare` and stay free (from the discs' field values, or the exact
// test's distance to the walls near the polygon, capped).
struct PoseCheck {
  bool collides = false;
  double spare = 0.0;
};

class FootprintCollisionChecker {
 public:
  // `walls` and `field` must outlive the checker. margin in m (>= 0); discs >= 1 for the cover.
  FootprintCollisionChecker(const StaticSegmentIndex& walls, const ClearanceField& field, Footprint footprint,
                            double margin, int discs = 8);

  bool Collides(const Pose2& pose) const { return Check(pose).collides; }
  PoseCheck Check(const Pose2& pose) const { return Check(pose, std::cos(pose.theta), std::sin(pose.theta)); }
  // The same with the heading's cosine and sine given (the planner's precomputed sweeps).
  PoseCheck Check(const Pose2& pose, double cos_theta, double sin_theta) const;
  // The exact test alone (no field), for tests and for poses the field does not cover.
  bool CollidesExactly(const Pose2& pose) const { return ExactSpare(pose, std::cos(pose.theta), std::sin(pose.theta)) < 0.0; }
  // The exact test with its spare: -1 in collision, else the least distance from the polygon
  // to the walls less the margin, capped at kExactSpareCap (walls farther than margin + cap
  // from the polygon's box are not measured).
  double ExactSpare(const Pose2& pose, double cos_theta, double sin_theta) const;
  static constexpr double kExactSpareCap = 0.3;  // m

  const Footprint& footprint() const { return footprint_; }
  const std::vector<Disc>& discs() const { return discs_; }
  double inscribed_radius() const { return inscribed_; }
  double circumscribed_radius() const { return circumscribed_; }
  double margin() const { return margin_; }
  const CollisionCounters& counters() const { return counters_; }

 private:
  const StaticSegmentIndex& walls_;
  const ClearanceField& field_;
  Footprint footprint_;
  double margin_, inscribed_, circumscribed_;
  std::vector<Disc> discs_;
  Eigen::Vector2d box_lo_, box_hi_;  // the polygon's bounding box (vehicle frame)
  bool box_footprint_ = false;       // the polygon is that box (a rectangle centred anyhow): the exact test's quick path
  mutable CollisionCounters counters_;
};

}  // namespace minenav
