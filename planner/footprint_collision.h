#pragma once
// Does the vehicle's polygon at a pose come within `margin` of a wall? Decided in three
// steps (the clearance field first, exact geometry only where it cannot tell):
//   clearance at the pose > circumscribed radius + margin (+ the field's slack): free;
//   clearance at the pose < inscribed radius + margin (- the slack): in collision (a wall
//     passes through the disc that the polygon contains, or within margin of it);
//   otherwise: the exact polygon-against-segment test against the walls near the pose
//     (common/segment_index.h): a wall end inside the polygon, or a wall within margin of an
//     edge, is a collision.

#include <cstdint>

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

class FootprintCollisionChecker {
 public:
  // `walls` and `field` must outlive the checker. margin in m (>= 0).
  FootprintCollisionChecker(const StaticSegmentIndex& walls, const ClearanceField& field, Footprint footprint,
                            double margin);

  bool Collides(const Pose2& pose) const;
  // The exact test alone (no field), for tests and for poses the field does not cover.
  bool CollidesExactly(const Pose2& pose) const;

  const Footprint& footprint() const { return footprint_; }
  double inscribed_radius() const { return inscribed_; }
  double circumscribed_radius() const { return circumscribed_; }
  double margin() const { return margin_; }
  const CollisionCounters& counters() const { return counters_; }

 private:
  const StaticSegmentIndex& walls_;
  const ClearanceField& field_;
  Footprint footprint_;
  double margin_, inscribed_, circumscribed_;
  mutable CollisionCounters counters_;
  mutable std::vector<Eigen::Vector2d> world_;  // the polygon at the pose being tested
};

}  // namespace minenav
