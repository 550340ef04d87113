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

#include <array>
#include <optional>
#include <vector>

#include "common/pose2.h"
#include "planner/motion.h"
#include "planner/motion_costs.h"

namespace minenav {

struct AnalyticShot {
  std::vector<MotionPiece> pieces;  // pieces of zero length left out
  double cost = 0.0;                // PieceCost summed, after the given previous direction
};

// The shots from `from` to `to` with arcs of `radius` (m), cheapest first, by their costs
// alone: a shot's pieces (its end poses: a sine and cosine a piece, and the allocations) are
// built only for the shots a caller gets to (the planner tries the cheapest first and mostly
// stops at the first or second). No allocation.
class ShotCandidates {
 public:
  ShotCandidates(const Pose2& from, const Pose2& to, double radius, const MotionCosts& costs,
                 int previous_direction = 0);
  int size() const { return count_; }
  // The i-th cheapest shot's cost (its pieces' PieceCost, within rounding), 0 <= i < size().
  double cost(int i) const { return words_[static_cast<size_t>(i)].cost; }
  // Its pieces; nullopt when rounding keeps them from ending at `to` within 1e-6 m and rad.
  std::optional<AnalyticShot> Build(int i) const;

 private:
  struct Word {
    int kind = 0;  // 0, 1: TIP-S-TIP forward, backing; 2 + 4 (side1 < 0) + 2 (side2 < 0) + (reverse): CSC
    double cost = 0.0;
  };
  static constexpr int kMaxWords = 10;
  Pose2 from_, to_;
  double radius_;
  MotionCosts costs_;
  int previous_direction_;
  std::array<Word, kMaxWords> words_{};
  int count_ = 0;
};

// Every shot from `from` to `to` with arcs of `radius` (m), cheapest first, built. Each shot
// ends at `to` within 1e-6 m and 1e-6 rad (one that would not, by rounding, is left out).
std::vector<AnalyticShot> AnalyticShots(const Pose2& from, const Pose2& to, double radius, const MotionCosts& costs,
                                        int previous_direction = 0);

// The cost of the cheapest of those shots (ShotCandidates' first, which is AnalyticShots'
// first but for a word AnalyticShots drops by rounding): the search's heuristic. Infinity
// when there is none.
double CheapestShotCost(const Pose2& from, const Pose2& to, double radius, const MotionCosts& costs,
                        int previous_direction = 0);

}  // namespace minenav
