#include <gtest/gtest.h>

#include <random>

#include "pose_estimator/iconic/brute_force_correspondence.h"
#include "pose_estimator/iconic/correspondence.h"
#include "pose_estimator/iconic/grid_search_correspondence.h"
#include "pose_estimator/iconic/iconic_test_world.h"
#include "pose_estimator/iconic/lookup_table_correspondence.h"
#include "pose_estimator/iconic/segment_map.h"

namespace minenav {
namespace {

std::vector<Segment> RandomSegments(int n, uint32_t seed, double extent, double max_len) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(0.0, extent), len(0.05, max_len), ang(-3.2, 3.2);
  std::vector<Segment> out;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d a(pos(rng), pos(rng));
    const double l = len(rng), t = ang(rng);
    out.emplace_back(a, a + l * Eigen::Vector2d(std::cos(t), std::sin(t)));
  }
  return out;
}

void ExpectAllAgree(const std::vector<Segment>& map, double cell, double reach, uint32_t seed) {
  BruteForceCorrespondence brute(map);
  GridSearchCorrespondence grid(map, cell);
  LookupTableCorrespondence lookup(map, cell, reach);
  std::mt19937 rng(seed);
  auto [centre, radius] = std::pair<Eigen::Vector2d, double>{Eigen::Vector2d(10, 6), 18.0};
  std::uniform_real_distribution<double> u(-1.0, 1.0), thr(0.0, reach);
  int matched = 0;
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector2d p = centre + radius * Eigen::Vector2d(u(rng), u(rng));
    const double t = thr(rng);
    const SegmentMatch b = brute.Nearest(p, t);
    const SegmentMatch g = grid.Nearest(p, t);
    const SegmentMatch l = lookup.Nearest(p, t);
    ASSERT_EQ(b.segment, g.segment) << "grid differs at " << p.transpose() << " threshold " << t;
    ASSERT_EQ(b.segment, l.segment) << "lookup differs at " << p.transpose() << " threshold " << t;
    if (b.matched()) {
      ++matched;
      EXPECT_DOUBLE_EQ(b.distance, l.distance);
      EXPECT_LE(b.distance, t);
      EXPECT_EQ(b.region, l.region);
    }
  }
  EXPECT_GT(matched, 1000);
}

TEST(CorrespondenceTest, AllThreeAgreeWithBruteForceOnRoom) {
  ExpectAllAgree(testing::RoomWorld(), 0.5, 2.0, 3);
  ExpectAllAgree(testing::RoomWorld(), 0.23, 3.0, 4);
}

TEST(CorrespondenceTest, AllThreeAgreeOnRandomShortSegments) {
  ExpectAllAgree(RandomSegments(300, 7, 20.0, 1.0), 0.3, 1.5, 5);
  ExpectAllAgree(RandomSegments(40, 8, 20.0, 8.0), 0.7, 2.5, 6);
}

TEST(CorrespondenceTest, NearestIsPerpendicularOrEndpoint) {
  BruteForceCorrespondence brute({{0, 0, 10, 0}});
  const SegmentMatch interior = brute.Nearest({3.0, 0.4}, 1.0);
  ASSERT_TRUE(interior.matched());
  EXPECT_EQ(interior.region, SegmentRegion::kInterior);
  EXPECT_NEAR(interior.distance, 0.4, 1e-12);
  const SegmentMatch end = brute.Nearest({10.3, 0.4}, 1.0);
  ASSERT_TRUE(end.matched());
  EXPECT_EQ(end.region, SegmentRegion::kEndPoint);
  EXPECT_NEAR(end.distance, 0.5, 1e-12);
  const SegmentMatch start = brute.Nearest({-0.3, -0.4}, 1.0);
  EXPECT_EQ(start.region, SegmentRegion::kStartPoint);
  EXPECT_FALSE(brute.Nearest({5.0, 1.2}, 1.0).matched());  // beyond the threshold
}

TEST(CorrespondenceTest, LookupTableMissesOnlyBeyondItsReach) {
  LookupTableCorrespondence lookup({{0, 0, 10, 0}}, 0.25, 1.0);
  EXPECT_TRUE(lookup.Nearest({5.0, 0.99}, 1.0).matched());
  EXPECT_FALSE(lookup.Nearest({5.0, 3.0}, 5.0).matched());      // outside the grown cells
  EXPECT_FALSE(lookup.Nearest({500.0, 3.0}, 5.0).matched());    // outside the grid
  EXPECT_FALSE(lookup.Nearest({std::nan(""), 0.0}, 5.0).matched());
}

TEST(CorrespondenceTest, LookupListsAreShort) {
  // 3.1.1: with a sensible cell size most lists hold 1-3 segments.
  LookupTableCorrespondence lookup(testing::RoomWorld(), 0.25, 2.0);
  EXPECT_LT(lookup.MeanListLength(), 2.0);
  EXPECT_LE(lookup.MaxListLength(), 8);
  EXPECT_GT(lookup.GrownCells(), 1000);
}

TEST(CorrespondenceTest, FactoryAndNames) {
  CorrespondenceMethod m;
  for (const char* name : {"brute", "grid", "lookup"}) {
    ASSERT_TRUE(ParseCorrespondenceMethod(name, &m));
    CorrespondenceOptions o;
    o.method = m;
    auto search = MakeCorrespondenceSearch(testing::RoomWorld(), o);
    EXPECT_STREQ(search->name(), name);
    EXPECT_EQ(search->segments().size(), testing::RoomWorld().size());
  }
  EXPECT_FALSE(ParseCorrespondenceMethod("fast", &m));
  EXPECT_DOUBLE_EQ(ChooseCellSize({{0, 0, 0.4, 0}, {0, 0, 0.6, 0}, {0, 0, 0.5, 0}}), 0.25);
}

TEST(SegmentMapTest, DropsZeroLengthDuplicateAndNonFinite) {
  const std::vector<Segment> raw = {{0, 0, 1, 0}, {1, 0, 0, 0},  {2, 2, 2, 2},
                                    {0, 0, 1, 0}, {std::nan(""), 0, 1, 1}, {0, 1, 1, 1}};
  const SegmentMap map = PrepareSegmentMap(raw);
  EXPECT_TRUE(map.problem.empty());
  ASSERT_EQ(map.segments.size(), 2u);
  EXPECT_EQ(map.dropped_duplicates, 2);
  EXPECT_EQ(map.dropped_zero_length, 1);
  EXPECT_EQ(map.dropped_nonfinite, 1);
  EXPECT_EQ(map.segments[0].b.x(), 1.0);  // first occurrence kept, in input order
}

TEST(SegmentMapTest, UnusableMapHasAReason) {
  const SegmentMap map = PrepareSegmentMap({{1, 1, 1, 1}, {2, 2, 2, 2}});
  EXPECT_TRUE(map.segments.empty());
  EXPECT_NE(map.problem.find("no usable segments"), std::string::npos) << map.problem;
  EXPECT_FALSE(PrepareSegmentMap({}).problem.empty());
}

// Issue 11, item 7: one 20 km segment in a map message sized the grid to its extent (GBs).
// The grid's cells grow instead; the answers stay the brute-force answers.
TEST(CorrespondenceTest, AHugeMapGetsCoarserCellsNotGigabytes) {
  std::vector<Segment> map = RandomSegments(200, 7, 20.0, 1.0);
  map.emplace_back(Eigen::Vector2d(0, 0), Eigen::Vector2d(20'000, 20'000));
  const double cell = CellSizeWithinBudget(map, ChooseCellSize(map), 0.5);
  EXPECT_GT(cell, 5.0);
  const double side = 20'001.0 / cell + 3.0;
  EXPECT_LE(side * side, kMaxGridCells * 1.1);
  EXPECT_DOUBLE_EQ(CellSizeWithinBudget(RandomSegments(50, 3, 20.0, 1.0), 0.2, 0.5), 0.2);  // small maps keep theirs
  CorrespondenceOptions options;
  options.max_distance = 0.5;
  const auto search = MakeCorrespondenceSearch(map, options);
  BruteForceCorrespondence brute(map);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 20.0);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector2d p(u(rng), u(rng));
    ASSERT_EQ(search->Nearest(p, 0.5).segment, brute.Nearest(p, 0.5).segment) << p.transpose();
  }
}

// Issue 16: a random-seed fuzz run's LINE_MAP, 11 short walls and one 127 km long, within
// kMaxGridCells at its 1 m cells but 890,000 cells grown (0.52 s in the release build, over
// 40 s in the fuzz build). The cells grow until the band fits its budget; the table grows no
// more cells than that, and its answers stay the brute-force ones.
TEST(CorrespondenceTest, ALongWallGetsCellsWhoseBandFitsTheBudget) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> y(0.0, 15.0);
  std::vector<Segment> map;
  map.emplace_back(Eigen::Vector2d(0, y(rng)), Eigen::Vector2d(127'000, y(rng)));
  for (int i = 0; i < 11; ++i) {
    const Eigen::Vector2d a(y(rng), y(rng));
    map.emplace_back(a, a + 0.3 * Eigen::Vector2d(y(rng), y(rng)));
  }
  const double reach = 3.0;
  EXPECT_GT(BandCells(map, 1.0, reach), 3.0 * kMaxBandCells);
  const double cell = CellSizeWithinBudget(map, 1.0, reach);
  EXPECT_GT(cell, 1.0);
  EXPECT_LE(BandCells(map, cell, reach), kMaxBandCells);
  EXPECT_GT(BandCells(map, cell / 1.05, reach), kMaxBandCells);  // the smallest such cell (5 % steps)
  const LookupTableCorrespondence table(map, cell, reach);
  EXPECT_LE(static_cast<double>(table.GrownCells()), kMaxBandCells);
  BruteForceCorrespondence brute(map);
  std::uniform_real_distribution<double> x(-10.0, 127'010.0), py(-5.0, 20.0);
  for (int i = 0; i < 6000; ++i) {
    const Eigen::Vector2d p(i % 2 ? x(rng) : 0.02 * x(rng), py(rng));  // half of them near the short walls
    ASSERT_EQ(table.Nearest(p, reach).segment, brute.Nearest(p, reach).segment) << p.transpose();
  }
  // A mine section's map keeps the cell it chose: 300 walls of up to 8 m in 200 m.
  const std::vector<Segment> section = RandomSegments(300, 9, 200.0, 8.0);
  EXPECT_DOUBLE_EQ(CellSizeWithinBudget(section, 0.5, reach), 0.5);
}

}  // namespace
}  // namespace minenav
