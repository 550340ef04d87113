#include "planner/analytic_shot.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace minenav {
namespace {

// The angle in [0, 2 pi).
double Mod2Pi(double a) {
  const double m = std::fmod(a, 2.0 * kPi);
  return m < 0.0 ? m + 2.0 * kPi : m;
}

void Add(std::vector<MotionPiece>& pieces, Motion motion, double amount, double radius) {
  if (std::abs(amount) < 1e-12) return;
  pieces.push_back({motion, amount, IsArc(motion) ? radius : 0.0, {}});
}

// Turn in place, straight (forward or reverse), turn in place.
std::vector<MotionPiece> TurnStraightTurn(const Pose2& a, const Pose2& b, bool reverse) {
  std::vector<MotionPiece> p;
  const double d = TranslationDistance(a, b);
  if (d < 1e-12) {
    Add(p, Motion::kTurnInPlace, NormalizeAngle(b.theta - a.theta), 0.0);
    return p;
  }
  const double heading = std::atan2(b.y - a.y, b.x - a.x) + (reverse ? kPi : 0.0);
  Add(p, Motion::kTurnInPlace, NormalizeAngle(heading - a.theta), 0.0);
  Add(p, reverse ? Motion::kReverse : Motion::kForward, d, 0.0);
  Add(p, Motion::kTurnInPlace, NormalizeAngle(b.theta - heading), 0.0);
  return p;
}

// The centre of the turning circle on `side` (+1 left, -1 right) of pose p, whose heading's
// cosine and sine are c and s.
Eigen::Vector2d Centre(const Pose2& p, double c, double s, int side, double r) {
  return {p.x - side * r * s, p.y + side * r * c};
}
Eigen::Vector2d Centre(const Pose2& p, int side, double r) {
  return Centre(p, std::cos(p.theta), std::sin(p.theta), side, r);
}

// The line from one turning circle's centre to another's: its length and heading.
struct CentreLine {
  double dist = 0.0, phi = 0.0;
};
CentreLine LineBetween(const Eigen::Vector2d& c1, const Eigen::Vector2d& c2) {
  const Eigen::Vector2d d = c2 - c1;
  return {d.norm(), std::atan2(d.y(), d.x())};
}

// The parts of a forward Dubins CSC word (side1, side2: +1 L, -1 R) from heading theta_a on
// the circle of side1 to heading theta_b on the circle of side2, `line` joining their
// centres: the first arc's and the last arc's turn (rad, in [0, 2 pi)) and the straight
// between (m); false if the word does not exist.
bool CscParts(double theta_a, double theta_b, const CentreLine& line, int side1, int side2, double r, double* turn1,
              double* straight, double* turn2) {
  *straight = line.dist;
  double psi = line.phi;  // tangent heading
  if (side1 != side2) {
    if (line.dist < 2.0 * r) return false;
    *straight = std::sqrt(line.dist * line.dist - 4.0 * r * r);
    psi = line.phi - side2 * std::atan2(2.0 * r, *straight);  // LSR: +, RSL: -
  }
  *turn1 = Mod2Pi(side1 * (psi - theta_a));
  *turn2 = Mod2Pi(side2 * (theta_b - psi));
  return true;
}

bool DubinsCscParts(const Pose2& a, const Pose2& b, int side1, int side2, double r, double* turn1, double* straight,
                    double* turn2) {
  return CscParts(a.theta, b.theta, LineBetween(Centre(a, side1, r), Centre(b, side2, r)), side1, side2, r, turn1,
                  straight, turn2);
}

// A forward Dubins CSC word from a to b; empty if it does not exist.
std::vector<MotionPiece> DubinsCsc(const Pose2& a, const Pose2& b, int side1, int side2, double r) {
  double turn1 = 0.0, straight = 0.0, turn2 = 0.0;
  if (!DubinsCscParts(a, b, side1, side2, r, &turn1, &straight, &turn2)) return {};
  std::vector<MotionPiece> p;
  const Motion arc1 = side1 > 0 ? Motion::kArcLeft : Motion::kArcRight;
  const Motion arc2 = side2 > 0 ? Motion::kArcLeft : Motion::kArcRight;
  Add(p, arc1, r * turn1, r);
  Add(p, Motion::kForward, straight, r);
  Add(p, arc2, r * turn2, r);
  return p;
}

Motion Reversed(Motion m) {
  // A forward path of the problem with headings turned by pi, driven backwards: a left turn
  // of the turned heading is a right arc in reverse, and the other way round.
  switch (m) {
    case Motion::kForward: return Motion::kReverse;
    case Motion::kArcLeft: return Motion::kArcRightReverse;
    case Motion::kArcRight: return Motion::kArcLeftReverse;
    default: return m;
  }
}

// Fills in the end poses; false when the pieces do not end at `to`.
bool Trace(const Pose2& from, const Pose2& to, std::vector<MotionPiece>& pieces) {
  Pose2 p = from;
  for (MotionPiece& piece : pieces) {
    p = PoseAfter(p, piece.motion, piece.amount, piece.radius);
    piece.end = p;
  }
  return TranslationDistance(p, to) < 1e-6 && HeadingDistance(p, to) < 1e-6;
}

// A word's pieces: kind 0, 1 TIP-S-TIP forward or backing; 2 + 4 (side1 < 0) + 2 (side2 < 0)
// + (reverse) a CSC word (ShotCandidates::Word). Empty when the CSC word does not exist.
std::vector<MotionPiece> WordPieces(const Pose2& from, const Pose2& to, double radius, int kind) {
  if (kind < 2) return TurnStraightTurn(from, to, kind == 1);
  const int c = kind - 2, s1 = (c & 4) ? -1 : 1, s2 = (c & 2) ? -1 : 1;
  if (!(c & 1)) return DubinsCsc(from, to, s1, s2, radius);
  const Pose2 from_turned(from.x, from.y, NormalizeAngle(from.theta + kPi));
  const Pose2 to_turned(to.x, to.y, NormalizeAngle(to.theta + kPi));
  std::vector<MotionPiece> back = DubinsCsc(from_turned, to_turned, s1, s2, radius);
  for (MotionPiece& piece : back) piece.motion = Reversed(piece.motion);
  return back;
}

}  // namespace

ShotCandidates::ShotCandidates(const Pose2& from, const Pose2& to, double radius, const MotionCosts& costs,
                               int previous_direction)
    : from_(from), to_(to), radius_(radius), costs_(costs), previous_direction_(previous_direction) {
  // PieceCost's rules on the pieces the words would have: a metre reversed costs
  // reverse_factor, a turn in place turn_in_place_per_rad per radian, the first driven piece
  // against previous_direction one direction_change; pieces under 1e-12 are left out, and a
  // word left with no piece is kept only where from and to are one pose (as AnalyticShots did).
  const auto drive = [&](double length, int direction) {
    if (length < 1e-12) return 0.0;
    const double change = previous_direction != 0 && direction != previous_direction ? costs.direction_change : 0.0;
    return length * (direction < 0 ? costs.reverse_factor : 1.0) + change;
  };
  const auto turn = [&](double a) { return std::abs(a) < 1e-12 ? 0.0 : costs.turn_in_place_per_rad * std::abs(a); };
  const bool same_pose = TranslationDistance(from, to) + HeadingDistance(from, to) <= 1e-9;
  const auto add = [&](int kind, double cost, bool empty) {
    if (!empty || same_pose) words_[static_cast<size_t>(count_++)] = {kind, cost};
  };
  const double d = TranslationDistance(from, to);
  if (d < 1e-12) {
    const double a = NormalizeAngle(to.theta - from.theta);
    for (const int kind : {0, 1}) add(kind, turn(a), std::abs(a) < 1e-12);
  } else {
    const double towards = std::atan2(to.y - from.y, to.x - from.x);
    for (const int kind : {0, 1}) {
      const double heading = towards + (kind == 1 ? kPi : 0.0);
      add(kind,
          turn(NormalizeAngle(heading - from.theta)) + drive(d, kind == 1 ? -1 : 1) +
              turn(NormalizeAngle(to.theta - heading)),
          false);
    }
  }
  // The CSC words: the problem with both headings turned by pi (driven in reverse) has its
  // left circle where the problem's right one is, so the four lines between the turning
  // circles' centres serve all eight words.
  const double from_turned = NormalizeAngle(from.theta + kPi), to_turned = NormalizeAngle(to.theta + kPi);
  const double cos_from = std::cos(from.theta), sin_from = std::sin(from.theta);
  const double cos_to = std::cos(to.theta), sin_to = std::sin(to.theta);
  CentreLine lines[2][2];  // [side1 < 0][side2 < 0], of the problem itself
  for (const int s1 : {1, -1})
    for (const int s2 : {1, -1})
      lines[s1 < 0][s2 < 0] =
          LineBetween(Centre(from, cos_from, sin_from, s1, radius), Centre(to, cos_to, sin_to, s2, radius));
  for (const int s1 : {1, -1})
    for (const int s2 : {1, -1})
      for (const int direction : {1, -1}) {
        double t1 = 0.0, straight = 0.0, t2 = 0.0;
        const bool exists = direction > 0 ? CscParts(from.theta, to.theta, lines[s1 < 0][s2 < 0], s1, s2, radius, &t1,
                                                     &straight, &t2)
                                          : CscParts(from_turned, to_turned, lines[s1 > 0][s2 > 0], s1, s2, radius,
                                                     &t1, &straight, &t2);
        if (!exists) continue;
        const double a1 = radius * t1, a2 = radius * t2;
        const double length = (a1 < 1e-12 ? 0.0 : a1) + (straight < 1e-12 ? 0.0 : straight) + (a2 < 1e-12 ? 0.0 : a2);
        add(2 + (s1 < 0 ? 4 : 0) + (s2 < 0 ? 2 : 0) + (direction < 0 ? 1 : 0), drive(length, direction),
            length < 1e-12);
      }
  std::sort(words_.begin(), words_.begin() + count_, [](const Word& a, const Word& b) { return a.cost < b.cost; });
}

std::optional<AnalyticShot> ShotCandidates::Build(int i) const {
  AnalyticShot shot;
  shot.pieces = WordPieces(from_, to_, radius_, words_[static_cast<size_t>(i)].kind);
  if (!Trace(from_, to_, shot.pieces)) return std::nullopt;
  int direction = previous_direction_;
  for (const MotionPiece& piece : shot.pieces) {
    shot.cost += PieceCost(piece, direction, costs_);
    if (DriveDirection(piece.motion) != 0) direction = DriveDirection(piece.motion);
  }
  return shot;
}

std::vector<AnalyticShot> AnalyticShots(const Pose2& from, const Pose2& to, double radius, const MotionCosts& costs,
                                        int previous_direction) {
  const ShotCandidates candidates(from, to, radius, costs, previous_direction);
  std::vector<AnalyticShot> shots;
  for (int i = 0; i < candidates.size(); ++i)
    if (std::optional<AnalyticShot> shot = candidates.Build(i)) shots.push_back(std::move(*shot));
  // Sorted by the built costs (the candidates' within rounding).
  std::stable_sort(shots.begin(), shots.end(), [](const AnalyticShot& a, const AnalyticShot& b) { return a.cost < b.cost; });
  return shots;
}

double CheapestShotCost(const Pose2& from, const Pose2& to, double radius, const MotionCosts& costs,
                        int previous_direction) {
  const ShotCandidates candidates(from, to, radius, costs, previous_direction);
  return candidates.size() > 0 ? candidates.cost(0) : std::numeric_limits<double>::infinity();
}

}  // namespace minenav
