#include "sim/mine_generator.h"

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <stdexcept>

#include "common/angle.h"
#include "sim/world.h"

namespace minenav {
namespace {

using Vec = Eigen::Vector2d;

// Chains segments (a -> b, endpoints shared exactly) into closed loops; returns each loop's
// vertices. Fails the test if a chain does not close.
std::vector<std::vector<Vec>> Loops(const std::vector<Segment>& segs) {
  std::map<std::pair<double, double>, size_t> from;
  for (size_t i = 0; i < segs.size(); ++i) from[{segs[i].a.x(), segs[i].a.y()}] = i;
  std::vector<bool> used(segs.size(), false);
  std::vector<std::vector<Vec>> loops;
  for (size_t i = 0; i < segs.size(); ++i) {
    if (used[i]) continue;
    std::vector<Vec> loop;
    size_t k = i;
    while (!used[k]) {
      used[k] = true;
      loop.push_back(segs[k].a);
      const auto it = from.find({segs[k].b.x(), segs[k].b.y()});
      if (it == from.end()) {
        ADD_FAILURE() << "open chain at " << segs[k].b.transpose();
        return loops;
      }
      k = it->second;
    }
    EXPECT_EQ(k, i) << "chain does not close on itself";
    loops.push_back(loop);
  }
  return loops;
}

struct Box {
  Vec lo, hi;
};
Box BoundingBox(const std::vector<Vec>& pts) {
  Box b{pts.front(), pts.front()};
  for (const Vec& p : pts) {
    b.lo = b.lo.cwiseMin(p);
    b.hi = b.hi.cwiseMax(p);
  }
  return b;
}

double SignedArea(const std::vector<Vec>& pts) {
  double a = 0.0;
  for (size_t i = 0; i < pts.size(); ++i) {
    const Vec& p = pts[i];
    const Vec& q = pts[(i + 1) % pts.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

double NearestWall(const Vec& p, const std::vector<Segment>& world) {
  double best = 1e300;
  for (const Segment& s : world) best = std::min(best, PointToSegmentDistance(p, s));
  return best;
}

// True if no two segments cross except at shared endpoints.
::testing::AssertionResult NoCrossings(const std::vector<Segment>& segs) {
  for (size_t i = 0; i < segs.size(); ++i)
    for (size_t j = i + 1; j < segs.size(); ++j) {
      const auto x = SegmentIntersection(segs[i], segs[j]);
      if (!x) continue;
      if ((*x - segs[i].a).norm() < 1e-9 || (*x - segs[i].b).norm() < 1e-9) continue;
      return ::testing::AssertionFailure() << "segments " << i << " and " << j << " cross at " << x->transpose();
    }
  return ::testing::AssertionSuccess();
}

TEST(MineGeneratorTest, PillarsRoomsAndSegmentLengths) {
  MineOptions o;
  o.pillar_rows = 3;
  o.pillar_cols = 5;
  const std::vector<Segment> mine = GenerateRoomAndPillarMine(o);
  for (const Segment& s : mine) ASSERT_LT(s.length(), o.max_segment_length);
  EXPECT_TRUE(NoCrossings(mine));
  const auto loops = Loops(mine);
  ASSERT_EQ(loops.size(), 1u + 3 * 5);  // boundary + pillars
  // Loop 0 is the boundary; the others pillars, in row-major order.
  const Vec panel = MinePanelSize(o);
  EXPECT_DOUBLE_EQ(panel.x(), 5 * 18.0 + 6.0);
  EXPECT_DOUBLE_EQ(panel.y(), 3 * 18.0 + 6.0);
  const double wobble = 2.0 * o.midpoint_displacement;  // bound on any wall's offset
  std::vector<Box> pillars;
  for (size_t k = 1; k < loops.size(); ++k) {
    const Box b = BoundingBox(loops[k]);
    pillars.push_back(b);
    EXPECT_NEAR(b.hi.x() - b.lo.x(), 12.0, 2 * wobble);
    EXPECT_NEAR(b.hi.y() - b.lo.y(), 12.0, 2 * wobble);
    EXPECT_NEAR(SignedArea(loops[k]), 144.0, 12.0 * 4 * wobble);  // counter-clockwise, ~144 m^2
    // Every vertex within `wobble` of the nominal square's outline.
    const int r = static_cast<int>(k - 1) / o.pillar_cols, c = static_cast<int>(k - 1) % o.pillar_cols;
    const Vec lo(6.0 + c * 18.0, 6.0 + r * 18.0);
    const std::vector<Segment> nominal{Segment(lo, lo + Vec(12, 0)), Segment(lo + Vec(12, 0), lo + Vec(12, 12)),
                                       Segment(lo + Vec(12, 12), lo + Vec(0, 12)), Segment(lo + Vec(0, 12), lo)};
    for (const Vec& v : loops[k]) ASSERT_LT(NearestWall(v, nominal), wobble + 1e-12);
  }
  // Rooms: the gap between neighbouring pillars is 6 m up to the wall wobble.
  for (int r = 0; r < o.pillar_rows; ++r)
    for (int c = 0; c + 1 < o.pillar_cols; ++c) {
      const double gap = pillars[r * o.pillar_cols + c + 1].lo.x() - pillars[r * o.pillar_cols + c].hi.x();
      EXPECT_NEAR(gap, 6.0, 2 * wobble);
    }
  // The walls really are displaced (fractal), not straight.
  double max_offset = 0.0;
  for (const Vec& v : loops[1]) {
    max_offset = std::max(max_offset, std::min({std::abs(v.x() - 6.0), std::abs(v.x() - 18.0),
                                                std::abs(v.y() - 6.0), std::abs(v.y() - 18.0)}));
  }
  EXPECT_GT(max_offset, 0.05);
  // Boundary encloses all pillars.
  const Box outer = BoundingBox(loops[0]);
  EXPECT_NEAR(outer.lo.x(), 0.0, wobble);
  EXPECT_NEAR(outer.hi.y(), panel.y(), wobble);
}

TEST(MineGeneratorTest, SeedReproducibility) {
  MineOptions o;
  const auto a = GenerateRoomAndPillarMine(o);
  const auto b = GenerateRoomAndPillarMine(o);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].a, b[i].a);
    ASSERT_EQ(a[i].b, b[i].b);
  }
  o.seed = 2;
  const auto c = GenerateRoomAndPillarMine(o);
  bool differs = c.size() != a.size();
  for (size_t i = 0; !differs && i < a.size(); ++i) differs = a[i].a != c[i].a;
  EXPECT_TRUE(differs);
  o.midpoint_displacement = 0.0;  // no randomness left: exact squares split in halves
  for (const Segment& s : GenerateRoomAndPillarMine(o)) {
    EXPECT_TRUE(s.a.x() == s.b.x() || s.a.y() == s.b.y());
  }
}

TEST(MineGeneratorTest, JsonRoundTripThroughWorld) {
  const auto mine = GenerateRoomAndPillarMine(MineOptions());
  const World w(mine);
  const World back = World::FromJson(w.ToJson(), "mine.json");
  const auto segs = back.Segments();
  ASSERT_EQ(segs.size(), mine.size());
  for (size_t i = 0; i < mine.size(); ++i) {
    EXPECT_NEAR((segs[i].a - mine[i].a).norm(), 0.0, 1e-7);
    EXPECT_NEAR((segs[i].b - mine[i].b).norm(), 0.0, 1e-7);
  }
}

TEST(MineGeneratorTest, InvalidOptionsGiveOneLineReasons) {
  MineOptions o;
  o.pillar_rows = 0;
  EXPECT_NE(ValidateMineOptions(o), "");
  EXPECT_THROW(GenerateRoomAndPillarMine(o), std::invalid_argument);
  o = MineOptions();
  o.max_segment_length = 0.0;
  EXPECT_NE(ValidateMineOptions(o).find("max_segment_length"), std::string::npos);
  o = MineOptions();
  o.midpoint_displacement = 2.0;
  EXPECT_NE(ValidateMineOptions(o).find("midpoint_displacement"), std::string::npos);
  EXPECT_EQ(ValidateMineOptions(MineOptions()), "");
}

TEST(MineGeneratorTest, SurveyStationsSerpentineInFreeSpace) {
  const MineOptions o;
  const auto mine = GenerateRoomAndPillarMine(o);
  const auto stations = MineSurveyStations(o, 42);
  ASSERT_EQ(stations.size(), 42u);
  const World world(mine);
  const Vec free_point(3.0, 3.0);  // a room corner: certainly free
  double min_gap = 1e9, max_gap = 0.0;
  for (size_t i = 0; i < stations.size(); ++i) {
    const Vec p = stations[i].pose.translation();
    EXPECT_GT(NearestWall(p, mine), 0.5 * o.room_width - 2 * o.midpoint_displacement - 1e-9);
    EXPECT_TRUE(world.SameSpace(p, free_point)) << i;
    if (i > 0) {
      const double d = (p - stations[i - 1].pose.translation()).norm();
      min_gap = std::min(min_gap, d);
      max_gap = std::max(max_gap, d);
    }
  }
  // Evenly spaced along the path (a corner cut makes a straight-line gap shorter).
  EXPECT_GT(min_gap, 3.0);
  EXPECT_LT(max_gap, 5.0);
  EXPECT_NEAR(stations.front().pose.x, 3.0, 1e-12);
  EXPECT_NEAR(stations.front().pose.y, 3.0, 1e-12);
  // Headings vary, around the travel direction.
  std::set<long> headings;
  for (const Station& s : stations) headings.insert(std::lround(RadToDeg(s.pose.theta)));
  EXPECT_GT(headings.size(), 20u);
  // Serpentine: starts eastwards along y = 3, ends on the top entry.
  EXPECT_NEAR(stations.back().pose.y, 2 * 18.0 + 3.0, 1e-9);
}

TEST(MineGeneratorTest, SurveySpacingCapInALargePanel) {
  MineOptions o;
  o.pillar_rows = 8;
  o.pillar_cols = 10;
  const auto spread = MineSurveyStations(o, 42);
  const auto dense = MineSurveyStations(o, 42, 0.6, 4.0);
  ASSERT_EQ(dense.size(), 42u);
  EXPECT_GT((spread[1].pose.translation() - spread[0].pose.translation()).norm(), 30.0);
  for (size_t i = 1; i < dense.size(); ++i)
    EXPECT_LE((dense[i].pose.translation() - dense[i - 1].pose.translation()).norm(), 4.0 + 1e-9);
  EXPECT_NEAR(dense.back().pose.x, 3.0 + 41 * 4.0, 1e-9);  // 164 m along the first 174 m entry
  // A cap larger than the even spread changes nothing.
  EXPECT_EQ(MineSurveyStations(MineOptions(), 42, 0.6, 50.0)[7].pose.x, MineSurveyStations(MineOptions(), 42)[7].pose.x);
}

TEST(MineGeneratorTest, LoopStationsCloseAroundOnePillar) {
  MineOptions o;
  const auto stations = LoopStations(o, 16, 1, 1);
  ASSERT_EQ(stations.size(), 16u);
  const double spacing = 4 * 18.0 / 16;
  for (size_t i = 0; i < stations.size(); ++i) {
    const Vec p = stations[i].pose.translation(), q = stations[(i + 1) % stations.size()].pose.translation();
    const double d = (p - q).norm();
    EXPECT_LE(d, spacing + 1e-9);
    EXPECT_GT(d, spacing / std::sqrt(2.0) - 1e-9);
    // On the centreline of the rooms around pillar (1, 1): [24, 36]^2 grown by 3 m.
    EXPECT_NEAR(std::max(std::abs(p.x() - 30.0), std::abs(p.y() - 30.0)), 9.0, 1e-9) << i;
  }
  EXPECT_THROW(LoopStations(o, 8, 5, 0), std::invalid_argument);
}

TEST(ResearchMineTest, IrregularPillarsCribsAndClearStations) {
  ResearchMineOptions o;
  const auto mine = GenerateResearchMine(o);
  for (const Segment& s : mine) ASSERT_LT(s.length(), std::max(o.max_segment_length, o.crib_size + 1e-9));
  const auto loops = Loops(mine);
  int pillars = 0, cribs = 0, posts = 0;
  std::set<long> widths;
  for (size_t k = 1; k < loops.size(); ++k) {
    const Box b = BoundingBox(loops[k]);
    const double w = b.hi.x() - b.lo.x(), h = b.hi.y() - b.lo.y();
    if (std::abs(w - o.crib_size) < 1e-9 && std::abs(h - o.crib_size) < 1e-9) {
      ++cribs;
    } else if (std::abs(w - o.post_size) < 1e-9 && std::abs(h - o.post_size) < 1e-9) {
      ++posts;
    } else {
      ++pillars;
      EXPECT_GT(w, o.pillar_size_min - 2 * (o.corner_jitter + 2 * o.midpoint_displacement));
      EXPECT_LT(w, o.pillar_size_max + 2 * (o.corner_jitter + 2 * o.midpoint_displacement));
      widths.insert(std::lround(10 * w));
    }
  }
  EXPECT_EQ(pillars, o.pillar_rows * o.pillar_cols);
  EXPECT_GT(widths.size(), 5u);  // not a regular grid of equal squares
  EXPECT_GT(cribs, 10);
  EXPECT_GT(posts, 5);
  // Blocks never overlap one another or the walls.
  EXPECT_TRUE(NoCrossings(mine));
  const auto stations = ResearchMineStations(o, 33);
  ASSERT_EQ(stations.size(), 33u);
  const World world(mine);
  for (size_t i = 0; i < stations.size(); ++i) {
    const Vec p = stations[i].pose.translation();
    EXPECT_GT(NearestWall(p, mine), 0.3) << i;
    EXPECT_TRUE(world.SameSpace(p, stations[0].pose.translation())) << i;
    if (i > 0) {
      EXPECT_LT((p - stations[i - 1].pose.translation()).norm(), 12.0);
    }
  }
  // Narrow entries: from each station the nearest wall is at most half the widest entry away
  // (plus wobble), i.e. 3-4 m entries.
  for (const Station& s : stations) {
    EXPECT_LT(NearestWall(s.pose.translation(), mine), 0.5 * o.entry_width_max + o.corner_jitter + 0.3);
  }
  o.entry_width_min = 1.5;
  EXPECT_NE(ValidateResearchMineOptions(o), "");
}

}  // namespace
}  // namespace minenav
