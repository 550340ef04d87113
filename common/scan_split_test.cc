#include "common/scan_split.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#include "common/angle.h"

namespace minenav {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A scan that owns its readings; View() is what the splitter sees.
struct TestScan {
  std::vector<Eigen::Vector2d> points;
  std::vector<double> ranges;
  double angle_step = 0.0;
  ScanReadings View() const { return {points, ranges, angle_step}; }
};

// `n` readings of a circle of `radius` m about the sensor, a full turn.
TestScan Ring(int n, double radius) {
  TestScan s;
  s.angle_step = 2.0 * kPi / n;
  for (int i = 0; i < n; ++i) {
    const double a = i * s.angle_step;
    s.points.emplace_back(radius * std::cos(a), radius * std::sin(a));
    s.ranges.push_back(radius);
  }
  return s;
}

// Pushes reading i of a ring out to `range` m (an object behind a gap, or nearer).
void MoveReading(TestScan* s, int i, double range) {
  const double a = i * s->angle_step;
  s->points[static_cast<size_t>(i)] = Eigen::Vector2d(range * std::cos(a), range * std::sin(a));
  s->ranges[static_cast<size_t>(i)] = range;
}

std::vector<int> Iota(int from, int to) {  // from .. to inclusive
  std::vector<int> v(static_cast<size_t>(to - from + 1));
  std::iota(v.begin(), v.end(), from);
  return v;
}

std::vector<int> Concat(std::vector<int> a, const std::vector<int>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

TEST(ScanSplitTest, SplitsWhereNeighboursJumpApartAndDropsShortPieces) {
  TestScan s;
  for (int i = 0; i < 10; ++i) s.points.emplace_back(0.1 * i, 1.0);        // readings 0-9
  for (int i = 0; i < 10; ++i) s.points.emplace_back(5.0 + 0.1 * i, 1.0);  // 10-19, 4.1 m on
  for (int i = 0; i < 2; ++i) s.points.emplace_back(9.0, 1.0 + 0.1 * i);   // 20-21, too few
  ScanSplitOptions o;
  o.wrap_around = WrapAround::kNever;
  const auto pieces = SplitScan(s.View(), o);
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_EQ(pieces[0].readings, Iota(0, 9));
  EXPECT_EQ(pieces[1].readings, Iota(10, 19));
  EXPECT_FALSE(pieces[0].closed);
  o.min_points = 2;
  EXPECT_EQ(SplitScan(s.View(), o).size(), 3u);
}

TEST(ScanSplitTest, AGapOfExactlyTheAllowedDistanceDoesNotBreak) {
  TestScan s;
  s.points = {{0.0, 1.0}, {0.5, 1.0}, {1.0, 1.0}, {1.5 + 1e-12, 1.0}};
  ScanSplitOptions o;
  o.wrap_around = WrapAround::kNever;
  o.min_points = 1;
  const auto pieces = SplitScan(s.View(), o);
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_EQ(pieces[0].readings, Iota(0, 2));
  EXPECT_EQ(pieces[1].readings, Iota(3, 3));
}

TEST(ScanSplitTest, MissingReadingsBreakOnlyBeyondTheLimit) {
  TestScan s;
  for (int i = 0; i < 20; ++i) s.points.emplace_back(0.1 * i, 1.0);
  s.points[5].x() = kNaN;                                            // one missing
  s.points[10].y() = std::numeric_limits<double>::infinity();        // two missing
  s.points[11] = Eigen::Vector2d(kNaN, kNaN);
  ScanSplitOptions o;
  o.wrap_around = WrapAround::kNever;
  o.min_points = 1;
  o.max_missing_readings = 0;
  auto pieces = SplitScan(s.View(), o);
  ASSERT_EQ(pieces.size(), 3u);
  EXPECT_EQ(pieces[0].readings, Iota(0, 4));
  EXPECT_EQ(pieces[1].readings, Iota(6, 9));
  EXPECT_EQ(pieces[2].readings, Iota(12, 19));
  o.max_missing_readings = 1;
  pieces = SplitScan(s.View(), o);
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_EQ(pieces[0].readings, Concat(Iota(0, 4), Iota(6, 9)));
  o.max_missing_readings = 2;  // 0.3 m from reading 9 to 12: still within the 0.5 m gap
  ASSERT_EQ(SplitScan(s.View(), o).size(), 1u);
  o.max_missing_readings = kAnyNumberOfMissingReadings;
  ASSERT_EQ(SplitScan(s.View(), o).size(), 1u);
  EXPECT_EQ(SplitScan(s.View(), o)[0].readings.size(), 17u);
}

TEST(ScanSplitTest, AllowedGapGrowsWithRange) {
  ScanSplitOptions o;
  o.break_distance = 0.3;
  o.break_range_factor = 0.05;
  EXPECT_DOUBLE_EQ(AllowedGap(10.0, 0.01, o), 0.8);
  EXPECT_DOUBLE_EQ(AllowedGap(0.0, 0.01, o), 0.3);
  // Two points 0.7 m apart: one partial scan 10 m out (gap 0.8 m), two at 1 m (0.35 m).
  TestScan s;
  s.points = {{10.0, 0.0}, {10.0, 0.7}};
  s.ranges = {10.0, 10.0};
  o.wrap_around = WrapAround::kNever;
  o.min_points = 1;
  EXPECT_EQ(SplitScan(s.View(), o).size(), 1u);
  s.ranges = {1.0, 1.0};
  EXPECT_EQ(SplitScan(s.View(), o).size(), 2u);
  s.ranges = {1.0, 10.0};  // the nearer reading decides
  EXPECT_EQ(SplitScan(s.View(), o).size(), 2u);
  s.ranges.clear();  // no ranges: break_distance alone
  EXPECT_EQ(SplitScan(s.View(), o).size(), 2u);
}

TEST(ScanSplitTest, AdaptiveGapIsTheGapOfAWallAtTheIncidenceAngle) {
  ScanSplitOptions o;
  o.break_incidence_angle = DegToRad(10.0);
  // 30 m out, readings 1° apart, incidence 10°: 30 sin 1° / sin 9° = 3.3469 m.
  EXPECT_NEAR(AllowedGap(30.0, DegToRad(1.0), o), 3.3469, 1e-4);
  EXPECT_NEAR(AllowedGap(30.0, -DegToRad(1.0), o), 3.3469, 1e-4);  // clockwise scans alike
  EXPECT_EQ(AllowedGap(2.0, DegToRad(1.0), o), 0.5);    // near: 0.22 m, the floor wins
  EXPECT_EQ(AllowedGap(30.0, DegToRad(10.0), o), 0.5);  // incidence not above the step: off
  EXPECT_EQ(AllowedGap(30.0, DegToRad(1.0), ScanSplitOptions{}), 0.5);
}

TEST(ScanSplitTest, FullTurnContinuesFromTheLastReadingsIntoTheFirst) {
  // 36 readings 10° apart on a 2 m circle (0.35 m apart), readings 10 and 20 pushed out
  // to 9 m: partial scans 0-9, 11-19 and 21-35, the last continuing into the first.
  TestScan s = Ring(36, 2.0);
  MoveReading(&s, 10, 9.0);
  MoveReading(&s, 20, 9.0);
  ScanSplitOptions o;
  auto pieces = SplitScan(s.View(), o);
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_EQ(pieces[0].readings, Concat(Iota(21, 35), Iota(0, 9)));
  EXPECT_EQ(pieces[1].readings, Iota(11, 19));
  EXPECT_FALSE(pieces[0].closed);
  o.seam_partial_scan_first = false;
  pieces = SplitScan(s.View(), o);
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_EQ(pieces[0].readings, Iota(11, 19));
  EXPECT_EQ(pieces[1].readings, Concat(Iota(21, 35), Iota(0, 9)));
  // Not a full turn (readings 5° apart), or told never to wrap: three partial scans.
  for (const bool half_turn : {true, false}) {
    TestScan t = s;
    ScanSplitOptions never;
    if (half_turn) {
      t.angle_step = 0.5 * s.angle_step;
    } else {
      never.wrap_around = WrapAround::kNever;
    }
    pieces = SplitScan(t.View(), never);
    ASSERT_EQ(pieces.size(), 3u) << half_turn;
    EXPECT_EQ(pieces[0].readings, Iota(0, 9));
    EXPECT_EQ(pieces[2].readings, Iota(21, 35));
  }
}

TEST(ScanSplitTest, FullTurnWithoutABreakIsClosed) {
  TestScan s = Ring(72, 2.0);  // readings 0.17 m apart, 0.35 m across a missing one
  auto pieces = SplitScan(s.View(), {});
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_TRUE(pieces[0].closed);
  EXPECT_EQ(pieces[0].readings, Iota(0, 71));
  // Reading 0 missing: the seam holds only if one missing reading is allowed.
  s.points[0].x() = kNaN;
  ScanSplitOptions o;
  pieces = SplitScan(s.View(), o);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_FALSE(pieces[0].closed);
  EXPECT_EQ(pieces[0].readings, Iota(1, 71));
  o.max_missing_readings = 1;
  EXPECT_TRUE(SplitScan(s.View(), o)[0].closed);
  o.wrap_around = WrapAround::kNever;
  EXPECT_FALSE(SplitScan(s.View(), o)[0].closed);
  // A lone reading has no seam to close.
  TestScan lone;
  lone.points = {{1.0, 0.0}};
  lone.angle_step = 2.0 * kPi;
  o.min_points = 1;
  o.wrap_around = WrapAround::kWhenEndsMeet;
  pieces = SplitScan(lone.View(), o);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_FALSE(pieces[0].closed);
}

TEST(ScanSplitTest, EndsThatMeetWrapWithoutBearings) {
  // Points alone (no ranges, no angle step): only kWhenEndsMeet joins the seam.
  TestScan s = Ring(36, 2.0);
  MoveReading(&s, 20, 50.0);
  s.ranges.clear();
  s.angle_step = 0.0;
  ScanSplitOptions o;
  EXPECT_EQ(SplitScan(s.View(), o).size(), 2u);  // kFullTurn: no turn known
  o.wrap_around = WrapAround::kWhenEndsMeet;
  const auto pieces = SplitScan(s.View(), o);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].readings, Concat(Iota(21, 35), Iota(0, 19)));
}

TEST(ScanSplitTest, EmptyAndAllMissingScansGiveNothing) {
  EXPECT_TRUE(SplitScan(TestScan{}.View(), {}).empty());
  TestScan s = Ring(8, 1.0);
  for (auto& p : s.points) p.y() = kNaN;
  ScanSplitOptions o;
  o.min_points = 1;
  EXPECT_TRUE(SplitScan(s.View(), o).empty());
  EXPECT_TRUE(CoversFullTurn(360, DegToRad(1.0)));
  EXPECT_TRUE(CoversFullTurn(359, -DegToRad(1.0)));  // one reading short of the seam
  EXPECT_FALSE(CoversFullTurn(358, DegToRad(1.0)));
  EXPECT_FALSE(CoversFullTurn(360, 0.0));
}

// The splitter restated straight from the header, another way round: every present reading
// that does not link to the present reading before it (cyclically, when the scan wraps)
// starts a partial scan, which runs on, round the seam if need be, to the next start.
std::vector<PartialScanReadings> ReferenceSplit(const TestScan& s, const ScanSplitOptions& o) {
  const int n = static_cast<int>(s.points.size());
  auto linked = [&](int from, int to) {
    const int steps = ((to - from) % n + n) % n;
    if (steps - 1 > o.max_missing_readings) return false;
    const double r = s.ranges.empty() ? 0.0 : std::min(s.ranges[static_cast<size_t>(from)], s.ranges[static_cast<size_t>(to)]);
    const double dphi = std::abs(s.angle_step), lambda = o.break_incidence_angle;
    double gap = o.break_distance + o.break_range_factor * r;
    if (lambda > dphi) gap = std::max(gap, r * std::sin(dphi) / std::sin(lambda - dphi));
    return (s.points[static_cast<size_t>(to)] - s.points[static_cast<size_t>(from)]).norm() <= gap;
  };
  std::vector<int> present;
  for (int i = 0; i < n; ++i)
    if (std::isfinite(s.points[static_cast<size_t>(i)].x()) && std::isfinite(s.points[static_cast<size_t>(i)].y()))
      present.push_back(i);
  const size_t m = present.size();
  if (m == 0) return {};
  const double dphi = std::abs(s.angle_step);
  const bool wraps = o.wrap_around == WrapAround::kWhenEndsMeet ||
                     (o.wrap_around == WrapAround::kFullTurn && dphi * n >= 2.0 * kPi - 1.5 * dphi);
  std::vector<bool> starts(m);
  for (size_t k = 0; k < m; ++k) {
    const bool continues = k > 0 ? linked(present[k - 1], present[k])
                                 : wraps && m >= 2 && linked(present[m - 1], present[0]);
    starts[k] = !continues;
  }
  std::vector<PartialScanReadings> out;
  if (std::find(starts.begin(), starts.end(), true) == starts.end()) {
    out.push_back({present, true});
  } else {
    for (size_t k = 0; k < m; ++k) {
      if (!starts[k]) continue;
      PartialScanReadings piece;
      size_t j = k;
      do {
        piece.readings.push_back(present[j]);
        j = (j + 1) % m;
      } while (!starts[j]);
      out.push_back(piece);
    }
    // The partial scan begun last crosses the seam when the first present reading starts none.
    if (!starts[0] && o.seam_partial_scan_first) std::rotate(out.begin(), out.end() - 1, out.end());
  }
  std::erase_if(out, [&](const auto& p) { return static_cast<int>(p.readings.size()) < o.min_points; });
  return out;
}

// A random scan about the sensor: a wavy range profile that meets itself across the seam,
// stretches pushed out behind gaps, missing readings (NaN or infinite), and a step that
// makes a full turn, one reading short of one, half a turn, or is unknown.
TestScan RandomScan(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int n = std::uniform_int_distribution<int>(0, 80)(rng);
  TestScan s;
  const double turns[] = {1.0, static_cast<double>(n) / (n + 1.0), 0.5, 0.0};
  s.angle_step = 2.0 * kPi * turns[rng() % 4] / std::max(n, 1) * (u(rng) < 0.5 ? 1.0 : -1.0);
  const double base = 1.0 + 9.0 * u(rng), wave = 0.3 * u(rng), missing = 0.15 * u(rng);
  double pushed = 0.0;
  for (int i = 0; i < n; ++i) {
    if (u(rng) < 0.08) pushed = u(rng) < 0.5 ? 0.0 : 3.0 * u(rng);  // a stretch behind a gap
    const double a = i * (s.angle_step == 0.0 ? 2.0 * kPi / n : s.angle_step);
    const double r = base + wave * std::sin(3.0 * a) + pushed + 0.02 * u(rng);
    s.points.emplace_back(r * std::cos(a), r * std::sin(a));
    s.ranges.push_back(r);
    if (u(rng) < missing) s.points.back()[rng() % 2] = u(rng) < 0.5 ? kNaN : -std::numeric_limits<double>::infinity();
  }
  if (u(rng) < 0.25) s.ranges.clear();
  return s;
}

ScanSplitOptions RandomOptions(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ScanSplitOptions o;
  o.break_distance = 0.05 + 0.8 * u(rng);
  o.break_range_factor = u(rng) < 0.5 ? 0.0 : 0.1 * u(rng);
  o.break_incidence_angle = u(rng) < 0.5 ? 0.0 : 0.6 * u(rng);
  const int missing[] = {0, 1, 2, kAnyNumberOfMissingReadings};
  o.max_missing_readings = missing[rng() % 4];
  const WrapAround wraps[] = {WrapAround::kNever, WrapAround::kFullTurn, WrapAround::kWhenEndsMeet};
  o.wrap_around = wraps[rng() % 3];
  o.seam_partial_scan_first = u(rng) < 0.5;
  o.min_points = std::uniform_int_distribution<int>(1, 5)(rng);
  return o;
}

bool CrossesTheSeam(const PartialScanReadings& p) {
  return !std::is_sorted(p.readings.begin(), p.readings.end());
}

TEST(ScanSplitTest, AgreesWithTheReferenceOnRandomScans) {
  std::mt19937 rng(12);
  int seam_joins = 0, closed = 0, several = 0, seam_last = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const TestScan s = RandomScan(rng);
    const ScanSplitOptions o = RandomOptions(rng);
    const auto got = SplitScan(s.View(), o);
    const auto want = ReferenceSplit(s, o);
    ASSERT_EQ(got.size(), want.size()) << "trial " << trial;
    for (size_t k = 0; k < got.size(); ++k) {
      ASSERT_EQ(got[k].readings, want[k].readings) << "trial " << trial << " piece " << k;
      ASSERT_EQ(got[k].closed, want[k].closed) << "trial " << trial << " piece " << k;
      seam_joins += CrossesTheSeam(got[k]);
      seam_last += CrossesTheSeam(got[k]) && k + 1 == got.size() && k > 0;
      closed += got[k].closed;
    }
    several += got.size() >= 3;
  }
  // The random scans reach every case, or the agreement would say little.
  EXPECT_GT(seam_joins, 500);
  EXPECT_GT(seam_last, 100);
  EXPECT_GT(closed, 200);
  EXPECT_GT(several, 2000);
}

}  // namespace
}  // namespace minenav
