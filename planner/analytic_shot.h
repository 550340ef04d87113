#pragma once
// Analytic shots for the miner's motion set: paths from one pose to another without
// obstacles, in closed form. Reeds-Shepp-like, for a vehicle that can also turn in place:
//   TIP-S-TIP   turn in place to face the goal (or to back towards it), straight, turn in
//               place to the goal heading: always exists;
//   CSC         the four Dubins words LSL, RSR, LSR, RSL at the one turning radius, driven
//               forward, and the same four driven in reverse (Dubins, "On curves of minimal
//               length...", Am. J. Math. 79, 1957; the reverse words are the forward words of
//               the problem with both headings turned by pi).
// Not the 48 Reeds-Shepp words: no cusp inside a shot; the search supplies those.

#include <vector>

#include "common/pose2.h"
#include "planner/motion.h"
#include "planner/motion_costs.h"

namespace minenav {

struct AnalyticShot {
  std::vector<MotionPiece> pieces;  // pieces of zero length left out
  double cost = 0.0;                // PieceCost summed, after the given previous direction
};

// Every shot from `from` to `to` with arcs of `radius` (m), cheapest first. Each shot ends at
// `to` within 1e-6 m and 1e-6 rad (one that would not, by rounding, is left out).
std::vector<AnalyticShot> AnalyticShots(const Pose2& from, const Pose2& to, double radius, const MotionCosts& costs,
                                        int previous_direction = 0);

// The cost of the cheapest of those shots (AnalyticShots(...).front().cost but for a word
// AnalyticShots drops by rounding), without building them: the search's heuristic. Infinity
// when there is none.
double CheapestShotCost(const Pose2& from, const Pose2& to, double radius, const MotionCosts& costs,
                        int previous_direction = 0);

}  // namespace minenav
