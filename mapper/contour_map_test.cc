#include "mapper/contour_map.h"

#include <gtest/gtest.h>

#include <random>
#include <set>

namespace minenav::mapper {
namespace {

std::vector<Eigen::Vector2d> Line(double x0, double x1, double y, int n) {
  std::vector<Eigen::Vector2d> p;
  for (int i = 0; i < n; ++i) p.emplace_back(x0 + (x1 - x0) * i / (n - 1), y);
  return p;
}

// Every segment within `radius` of p, by brute force over the whole map.
std::set<SegmentRef> BruteForceNear(const ContourMap& map, const Eigen::Vector2d& p, double radius) {
  std::set<SegmentRef> out;
  for (const auto& [id, c] : map.contours())
    for (int k = 0; k < c.NumSegments(); ++k)
      if (PointToSegmentDistance(p, c.GetSegment(k)) <= radius) out.insert({id, k});
  return out;
}

// The grid must return a superset of the brute-force answer, and nothing stale.
void ExpectIndexCorrect(const ContourMap& map, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-15, 25);
  for (int q = 0; q < 200; ++q) {
    const Eigen::Vector2d p(u(rng), u(rng));
    const auto truth = BruteForceNear(map, p, 1.5);
    const auto got = map.SegmentsNear(p, 1.5);
    for (const SegmentRef& r : got) {
      const Contour* c = map.Find(r.contour);
      ASSERT_NE(c, nullptr) << "stale contour " << r.contour;
      ASSERT_LT(r.segment, c->NumSegments()) << "stale segment";
    }
    const std::set<SegmentRef> got_set(got.begin(), got.end());
    for (const SegmentRef& r : truth) ASSERT_TRUE(got_set.count(r)) << r.contour << ":" << r.segment;
  }
}

TEST(ContourTest, SegmentsOfOpenAndClosed) {
  Contour c;
  c.points = {{0, 0}, {1, 0}, {1, 1}};
  EXPECT_EQ(c.NumSegments(), 2);
  c.closed = true;
  EXPECT_EQ(c.NumSegments(), 3);
  EXPECT_EQ(c.GetSegment(2).b, Eigen::Vector2d(0, 0));
  EXPECT_NEAR(c.Length(), 2 + std::sqrt(2.0), 1e-12);
}

TEST(ContourTest, ResampleKeepsEndsAndSpacing) {
  const auto r = ResamplePolyline({{0, 0}, {10, 0}, {10, 3}}, false, 0.5);
  EXPECT_EQ(r.size(), 27u);
  EXPECT_EQ(r.front(), Eigen::Vector2d(0, 0));
  EXPECT_EQ(r.back(), Eigen::Vector2d(10, 3));
  EXPECT_NEAR(PolylineLength(r, false), 13.0, 0.02);  // only the corner is cut
  const auto c = ResamplePolyline({{0, 0}, {4, 0}, {4, 4}, {0, 4}}, true, 0.5);
  EXPECT_EQ(c.size(), 32u);
  EXPECT_NEAR(PolylineLength(c, true), 16.0, 1e-9);
}

TEST(ContourMapTest, CreateCutDetachExtendJoinKeepIdsAndGeometry) {
  ContourMap map(1.0);
  const int a = map.Create(Line(0, 10, 0, 11));
  const int b = map.Create(Line(12, 20, 0, 9));
  EXPECT_NE(a, b);
  EXPECT_EQ(map.NumSegments(), 18);

  const int v = map.Cut(a, 3, {3.5, 0.0});
  EXPECT_EQ(v, 4);
  EXPECT_EQ(map.Get(a).points[4], Eigen::Vector2d(3.5, 0));
  const auto tail = map.Detach(a, v);
  ASSERT_TRUE(tail);
  EXPECT_EQ(map.Get(a).points.back(), Eigen::Vector2d(3.5, 0));
  EXPECT_EQ(map.Get(*tail).points.front(), Eigen::Vector2d(3.5, 0));
  EXPECT_FALSE(map.Detach(a, 0));  // nothing to split at an end

  map.ExtendEnd(b, {{21, 0}, {22, 0}});
  map.ExtendStart(b, {{11, 0}});
  EXPECT_EQ(map.Get(b).points.front(), Eigen::Vector2d(11, 0));
  EXPECT_EQ(map.Get(b).points.back(), Eigen::Vector2d(22, 0));

  const int joined = map.Join(*tail, b, {{10.5, 0.0}});
  EXPECT_EQ(joined, *tail);
  EXPECT_EQ(map.Find(b), nullptr);
  EXPECT_NEAR(map.Get(joined).Length(), 22 - 3.5, 1e-12);
  ExpectIndexCorrect(map, 1);
}

TEST(ContourMapTest, JoinOntoItselfClosesAndDetachReopens) {
  ContourMap map;
  const int a = map.Create({{0, 0}, {4, 0}, {4, 4}, {0, 4}});
  EXPECT_EQ(map.Join(a, a, {{0, 2}}), a);
  EXPECT_TRUE(map.Get(a).closed);
  EXPECT_EQ(map.Get(a).NumSegments(), 5);
  EXPECT_NEAR(map.Get(a).Length(), 16.0, 1e-12);
  EXPECT_EQ(map.Detach(a, 2).value(), a);
  EXPECT_FALSE(map.Get(a).closed);
  EXPECT_EQ(map.Get(a).points.front(), Eigen::Vector2d(4, 4));
  EXPECT_EQ(map.Get(a).points.back(), Eigen::Vector2d(4, 4));
  EXPECT_NEAR(map.Get(a).Length(), 16.0, 1e-12);
  ExpectIndexCorrect(map, 2);
}

TEST(ContourMapTest, SpliceABoxIntoAWallLeavesTheOccludedPartAlone) {
  // The vending machine of 4.8: a wall along y = 0 sensed from above (free space y > 0 on
  // the left, so the wall runs left to right), a box in front of it from x = 4 to 6.
  ContourMap map;
  const int wall = map.Create(Line(0, 10, 0, 11));
  const int box = map.Create({{4, 0}, {4, 1}, {6, 1}, {6, 0}});
  // Attach the box's start where it meets the wall at x = 3.5 (segment 3 runs 3 -> 4).
  const auto first = map.Splice(wall, 3, {3.5, 0}, box, ContourMap::SpliceSide::kAttachStartAfterCut);
  EXPECT_EQ(first.joined, wall);
  ASSERT_GE(first.remainder, 0);
  // The remainder (3.5 .. 10) gets the box's end spliced in at x = 6.5.
  const Contour& rem = map.Get(first.remainder);
  int seg = -1;
  for (int k = 0; k < rem.NumSegments(); ++k) {
    const Segment s = rem.GetSegment(k);
    if (s.a.x() <= 6.5 && s.b.x() >= 6.5) seg = k;
  }
  ASSERT_GE(seg, 0);
  const auto second = map.Splice(first.remainder, seg, {6.5, 0}, wall, ContourMap::SpliceSide::kAttachEndBeforeCut);
  // One contour runs wall .. box .. wall; the occluded piece 3.5 .. 6.5 stays on its own.
  const Contour& through = map.Get(second.joined);
  EXPECT_EQ(through.points.front(), Eigen::Vector2d(0, 0));
  EXPECT_EQ(through.points.back(), Eigen::Vector2d(10, 0));
  EXPECT_NEAR(through.Length(), 3.5 + 0.5 + 1 + 2 + 1 + 0.5 + 3.5, 1e-12);
  const Contour& hidden = map.Get(second.remainder);
  EXPECT_EQ(hidden.points.front(), Eigen::Vector2d(3.5, 0));
  EXPECT_EQ(hidden.points.back(), Eigen::Vector2d(6.5, 0));
  EXPECT_EQ(map.NumContours(), 2);
  ExpectIndexCorrect(map, 3);
}

TEST(ContourMapTest, RemoveDegenerateSegmentsMergesShortOnes) {
  ContourMap map;
  const int a = map.Create({{0, 0}, {1, 0}, {1.02, 0}, {2, 0}, {2.0, 0.01}});
  EXPECT_EQ(map.RemoveDegenerateSegments(a, 0.1), 2);
  const Contour& c = map.Get(a);
  EXPECT_EQ(c.NumPoints(), 3);
  EXPECT_EQ(c.points.front(), Eigen::Vector2d(0, 0));
  EXPECT_EQ(c.points.back(), Eigen::Vector2d(2.0, 0.01));  // end vertices stay put
  const int tiny = map.Create({{5, 5}, {5.01, 5}});
  map.RemoveDegenerateSegments(tiny, 0.1);
  EXPECT_EQ(map.Find(tiny), nullptr);
}

TEST(ContourMapTest, RemoveSpikesKeepsCornersAndDropsFoldBacks) {
  ContourMap map;
  // A wall along y = 0 with a spike at x = 2 and a real 90 degree corner at x = 4.
  const int a = map.Create({{0, 0}, {1, 0}, {1.9, 0}, {2.0, -0.6}, {2.1, 0}, {3, 0}, {4, 0}, {4, 1}});
  EXPECT_EQ(map.RemoveSpikes(a, 2.4), 1);
  const Contour& c = map.Get(a);
  EXPECT_EQ(c.NumPoints(), 7);
  for (const auto& p : c.points) EXPECT_GE(p.y(), 0.0);
  EXPECT_EQ(c.points.back(), Eigen::Vector2d(4, 1));
}

TEST(ContourMapTest, IndexStaysCorrectUnderRandomEdits) {
  ContourMap map(1.5);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-10, 20);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  for (int round = 0; round < 300; ++round) {
    const auto ids = map.Ids();
    const int op = ids.empty() ? 0 : static_cast<int>(rng() % 7);
    const int id = ids.empty() ? -1 : ids[rng() % ids.size()];
    const Contour* c = ids.empty() ? nullptr : &map.Get(id);
    switch (op) {
      case 0: {
        const Eigen::Vector2d s(u(rng), u(rng));
        map.Create({s, s + Eigen::Vector2d(2, 0.5), s + Eigen::Vector2d(3, 2)});
        break;
      }
      case 1:
        map.Cut(id, static_cast<int>(rng() % c->NumSegments()),
                c->points[0] + Eigen::Vector2d(jitter(rng), jitter(rng)));
        break;
      case 2:
        map.Detach(id, static_cast<int>(rng() % c->NumPoints()));
        break;
      case 3:
        if (!c->closed) map.ExtendEnd(id, {c->points.back() + Eigen::Vector2d(1.0, jitter(rng))});
        break;
      case 4: {
        std::vector<Eigen::Vector2d> moved = c->points;
        for (auto& p : moved) p += Eigen::Vector2d(jitter(rng) * 5, jitter(rng) * 5);
        map.SetPoints(id, moved);
        break;
      }
      case 5: {
        const int other = ids[rng() % ids.size()];
        if (!c->closed && !map.Get(other).closed && (other != id || c->NumPoints() >= 3)) map.Join(id, other);
        break;
      }
      case 6:
        if (rng() % 3 == 0) map.Remove(id);
        break;
    }
    if (round % 30 == 0) ExpectIndexCorrect(map, static_cast<unsigned>(round));
  }
  ExpectIndexCorrect(map, 99);
  size_t expected_min = 0;
  for (const auto& [id, c] : map.contours()) expected_min += static_cast<size_t>(c.NumSegments());
  EXPECT_GE(map.grid().NumEntries(), expected_min);
}

}  // namespace
}  // namespace minenav::mapper
