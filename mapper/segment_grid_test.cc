#include "mapper/segment_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <random>

namespace minenav::mapper {
namespace {

Contour Line(int id, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  Contour c;
  c.id = id;
  c.points = {a, b};
  return c;
}

bool Contains(const std::vector<SegmentRef>& refs, const SegmentRef& r) {
  return std::find(refs.begin(), refs.end(), r) != refs.end();
}

double SecondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Issue 11, item 7: one 20 km diagonal segment covers 10^8 cells of 2 m in its bounding box;
// listing it in each took 6 GB and 18-39 s until bad_alloc. Now it costs one entry.
TEST(SegmentGridTest, A20KilometreSegmentCostsOneEntryNotItsBoundingBox) {
  SegmentGrid grid(2.0);
  const auto t0 = std::chrono::steady_clock::now();
  grid.Insert(Line(7, {0, 0}, {20000, 20000}));
  EXPECT_LT(SecondsSince(t0), 0.1);
  EXPECT_EQ(grid.NumEntries(), 1u);
  EXPECT_EQ(grid.NumUnindexed(), 1u);
  // Still found where it is (every query returns it; callers test the exact distance).
  EXPECT_TRUE(Contains(grid.QueryPoint({10000, 10000.5}, 1.0), SegmentRef{7, 0}));
  int visits = 0;
  grid.ForEachNear({15000, 15000}, 0.5, [&](const SegmentRef& r) { visits += r == SegmentRef{7, 0} ? 1 : 0; });
  EXPECT_EQ(visits, 1);
  grid.Remove(7);
  EXPECT_EQ(grid.NumEntries(), 0u);
  EXPECT_TRUE(grid.QueryPoint({10000, 10000}, 1.0).empty());
}

// A 1.5 km wall drawn as one diagonal segment: listed in the cells along it (at most three
// per 2 m column, some 1600), not the 280 000 of its box, and found from every point near it
// but not from afar.
TEST(SegmentGridTest, ALongSegmentIsListedAlongItsLine) {
  SegmentGrid grid(2.0);
  grid.Insert(Line(1, {-300, 100}, {760, 1160}));
  EXPECT_EQ(grid.NumUnindexed(), 0u);
  EXPECT_GT(grid.NumEntries(), 530u);   // at least one cell per 2 m column
  EXPECT_LT(grid.NumEntries(), 1700u);  // at most three per column
  for (double f = 0.0; f <= 1.0; f += 0.01) {
    const Eigen::Vector2d on = Eigen::Vector2d(-300, 100) + f * Eigen::Vector2d(1060, 1060);
    EXPECT_TRUE(Contains(grid.QueryPoint(on + Eigen::Vector2d(0.3, -0.3), 0.5), SegmentRef{1, 0})) << f;
  }
  EXPECT_FALSE(Contains(grid.QueryPoint({500, 100}, 5.0), SegmentRef{1, 0}));
}

// The walk along a segment must never miss a cell it passes through: for random long
// segments at every slope, every query point within `radius` of a segment gets it back.
TEST(SegmentGridTest, LineIndexingMissesNoSegmentNearAQueryPoint) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord(-400.0, 400.0), unit(0.0, 1.0), offset(-1.0, 1.0);
  SegmentGrid grid(2.0);
  std::vector<Segment> segments;
  for (int id = 0; id < 60; ++id) {
    const Eigen::Vector2d a(coord(rng), coord(rng)), b(coord(rng), coord(rng));
    segments.emplace_back(a, b);
    grid.Insert(Line(id, a, b));
  }
  EXPECT_EQ(grid.NumUnindexed(), 0u);
  int checked = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const int id = static_cast<int>(rng() % segments.size());
    const Segment& s = segments[static_cast<size_t>(id)];
    const double radius = 0.05 + unit(rng);
    const Eigen::Vector2d near = s.a + unit(rng) * (s.b - s.a) + radius * Eigen::Vector2d(offset(rng), offset(rng)) / 1.5;
    if (PointToSegmentDistance(near, s) > radius) continue;
    ++checked;
    ASSERT_TRUE(Contains(grid.QueryPoint(near, radius), SegmentRef{id, 0})) << trial;
    bool seen = false;
    grid.ForEachNear(near, radius, [&](const SegmentRef& r) { seen = seen || r == SegmentRef{id, 0}; });
    ASSERT_TRUE(seen) << trial;
  }
  EXPECT_GT(checked, 10000);
}

// Coordinates no map has (1e300, NaN) index without undefined behaviour and are returned.
TEST(SegmentGridTest, CoordinatesBeyondTheCellRangeAreKeptAsCandidates) {
  SegmentGrid grid(2.0);
  grid.Insert(Line(3, {1e300, 0}, {1e300, 1}));
  grid.Insert(Line(4, {0, 0}, {std::nan(""), 1}));
  grid.Insert(Line(5, {0, 0}, {1, 0}));
  EXPECT_EQ(grid.NumUnindexed(), 2u);
  const std::vector<SegmentRef> near = grid.QueryPoint({0.5, 0}, 0.1);
  EXPECT_TRUE(Contains(near, SegmentRef{3, 0}));
  EXPECT_TRUE(Contains(near, SegmentRef{4, 0}));
  EXPECT_TRUE(Contains(near, SegmentRef{5, 0}));
  EXPECT_FALSE(Contains(grid.QueryPoint({-1e12, 3e15}, 1.0), SegmentRef{5, 0}));
}

// The segments the mapper makes (0.5 m, a few cells) are listed in every cell of their box,
// as before.
TEST(SegmentGridTest, ShortSegmentsAreListedInTheirBoundingBox) {
  SegmentGrid grid(2.0);
  grid.Insert(Line(2, {1.5, 1.5}, {2.5, 2.5}));  // box over cells (0..1, 0..1)
  EXPECT_EQ(grid.NumEntries(), 4u);
  EXPECT_TRUE(Contains(grid.QueryPoint({3.9, 0.1}, 0.0), SegmentRef{2, 0}));  // cell (1, 0), off the line
}

}  // namespace
}  // namespace minenav::mapper
