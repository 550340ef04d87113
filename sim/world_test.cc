#include "sim/world.h"

#include <gtest/gtest.h>

#include "common/angle.h"
#include "common/file_io.h"

namespace minenav {
namespace {

using Vec = Eigen::Vector2d;

// A 30 x 30 m room with a 10 x 10 m pillar of coal in the middle (two closed loops).
World RoomWithPillar() {
  World w;
  w.AddPolygon({Vec(0, 0), Vec(30, 0), Vec(30, 30), Vec(0, 30)});
  w.AddPolygon({Vec(10, 10), Vec(20, 10), Vec(20, 20), Vec(10, 20)});
  return w;
}

double TotalLength(const World& w) {
  double l = 0.0;
  for (const Segment& s : w.Segments()) l += s.length();
  return l;
}

TEST(WorldTest, StableIdsAndVersion) {
  World w;
  EXPECT_EQ(w.version(), 0u);
  const int a = w.AddSegment(Segment(0, 0, 1, 0));
  const int b = w.AddSegment(Segment(0, 1, 1, 1));
  EXPECT_EQ(w.version(), 2u);
  EXPECT_NE(a, b);
  EXPECT_TRUE(w.RemoveSegment(a));
  EXPECT_FALSE(w.RemoveSegment(a));
  EXPECT_EQ(w.version(), 3u);  // failed removal changes nothing
  const int c = w.AddSegment(Segment(5, 5, 6, 6));
  EXPECT_NE(c, a);  // ids are never reused
  ASSERT_TRUE(w.Find(b).has_value());
  EXPECT_EQ(w.Find(b)->a, Vec(0, 1));
  EXPECT_FALSE(w.Find(a).has_value());
  EXPECT_EQ(w.Ids(), (std::vector<int>{b, c}));
  const auto ids = w.AddPolygon({Vec(0, 0), Vec(1, 0), Vec(1, 1)});
  EXPECT_EQ(ids.size(), 3u);
  EXPECT_EQ(w.size(), 5u);
  EXPECT_EQ(w.RemoveSegments(ids), 3);
  EXPECT_EQ(w.size(), 2u);
  const uint64_t v = w.version();
  const auto face = w.ReplaceSegments({b}, {Segment(0, 2, 1, 2), Segment(1, 2, 2, 2)});
  EXPECT_EQ(w.version(), v + 1);
  EXPECT_FALSE(w.Contains(b));
  EXPECT_TRUE(w.Contains(face[0]) && w.Contains(face[1]));
}

TEST(WorldTest, JsonRoundTripAndBadInput) {
  const World w = RoomWithPillar();
  const std::string path = ::testing::TempDir() + "/world_test.json";
  w.Save(path);
  const World back = World::Load(path);
  ASSERT_EQ(back.size(), w.size());
  EXPECT_EQ(back.Segments()[5].a, w.Segments()[5].a);
  EXPECT_THROW(World::FromJson("{\"segments\": [[1, 2, 3]]}", "bad.json"), InputError);
  EXPECT_THROW(World::FromJson("not json", "bad.json"), InputError);
  EXPECT_THROW(World::Load(::testing::TempDir() + "/does_not_exist.json"), InputError);
}

TEST(WorldTest, SameSpaceByParity) {
  const World w = RoomWithPillar();
  const Vec free(5, 5);
  EXPECT_TRUE(w.SameSpace(Vec(25, 25), free));
  EXPECT_TRUE(w.SameSpace(Vec(15, 5), free));  // below the pillar
  EXPECT_TRUE(w.SameSpace(Vec(5, 10), free));  // exactly level with the pillar's bottom edge
  EXPECT_FALSE(w.SameSpace(Vec(15, 15), free));
  EXPECT_FALSE(w.SameSpace(Vec(-5, 15), free));
}

TEST(WorldTest, CutRegionAdvancesTheFace) {
  World w = RoomWithPillar();
  const double before = TotalLength(w);
  const uint64_t v = w.version();
  // Cut 2 m deep into the pillar's west face, over y in [13, 17], from the room at x = 8.
  const CutResult cut = w.CutRegion({Vec(8, 13), Vec(12, 13), Vec(12, 17), Vec(8, 17)}, Vec(5, 5));
  EXPECT_EQ(w.version(), v + 1);
  EXPECT_EQ(cut.removed_ids.size(), 1u);  // the west face
  EXPECT_NEAR(cut.new_face_length, 2 + 4 + 2, 1e-12);
  // Old face lost 4 m, new face added 8 m.
  EXPECT_NEAR(TotalLength(w), before - 4 + 8, 1e-9);
  EXPECT_TRUE(w.SameSpace(Vec(11, 15), Vec(5, 5)));   // cut: now free
  EXPECT_FALSE(w.SameSpace(Vec(13, 15), Vec(5, 5)));  // beyond the cut: still coal
  EXPECT_FALSE(w.SameSpace(Vec(11, 12), Vec(5, 5)));  // beside the cut: still coal
  // A ray from the room along y = 15 now meets the advanced face at x = 12.
  const auto hit = CastRay(Vec(5, 15), 0.0, w.Segments(), 100.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->range, 7.0, 1e-12);
  // A second, deeper cut in the same place advances it again by 1.5 m.
  w.CutRegion({Vec(11, 13), Vec(13.5, 13), Vec(13.5, 17), Vec(11, 17)}, Vec(5, 5));
  EXPECT_NEAR(CastRay(Vec(5, 15), 0.0, w.Segments(), 100.0)->range, 8.5, 1e-12);
  EXPECT_NEAR(TotalLength(w), before - 4 + 8 + 3, 1e-9);
  // Cutting only free space changes nothing.
  const uint64_t v2 = w.version();
  const CutResult none = w.CutRegion({Vec(2, 2), Vec(4, 2), Vec(4, 4), Vec(2, 4)}, Vec(5, 5));
  EXPECT_TRUE(none.removed_ids.empty());
  EXPECT_TRUE(none.added_ids.empty());
  EXPECT_EQ(w.version(), v2);
}

TEST(WorldTest, CutThroughAPillarCorner) {
  World w = RoomWithPillar();
  // A 4 x 4 box centred on the pillar's south-west corner.
  w.CutRegion({Vec(8, 8), Vec(12, 8), Vec(12, 12), Vec(8, 12)}, Vec(5, 5));
  EXPECT_TRUE(w.SameSpace(Vec(11, 11), Vec(5, 5)));
  EXPECT_FALSE(w.SameSpace(Vec(12.5, 12.5), Vec(5, 5)));
  EXPECT_FALSE(w.SameSpace(Vec(11, 13), Vec(5, 5)));
  const auto hit = CastRay(Vec(5, 11), 0.0, w.Segments(), 100.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->range, 7.0, 1e-12);  // meets the new face at x = 12
  const auto hit2 = CastRay(Vec(5, 13), 0.0, w.Segments(), 100.0);
  EXPECT_NEAR(hit2->range, 5.0, 1e-12);  // the old face above the cut
}

TEST(WorldTest, CutFlushWithAFaceAddsNoDuplicateWall) {
  World w = RoomWithPillar();
  // The box [10, 12] x [10, 14] inside the pillar shares its south-west corner: its west and
  // south edges lie on the pillar's faces (which go, the room being on their other side), its
  // east and north edges become the new face.
  const CutResult cut = w.CutRegion({Vec(10, 10), Vec(12, 10), Vec(12, 14), Vec(10, 14)}, Vec(5, 5));
  EXPECT_NEAR(cut.new_face_length, 2 + 4, 1e-12);  // east and north edges of the box only
  const auto hit = CastRay(Vec(5, 12), 0.0, w.Segments(), 100.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->range, 7.0, 1e-12);
  const auto up = CastRay(Vec(11, 5), kPi / 2, w.Segments(), 100.0);
  EXPECT_NEAR(up->range, 9.0, 1e-12);  // through the cut to the new north face at y = 14
  // The old faces stay where they still bound coal, and nowhere is a wall doubled.
  EXPECT_NEAR(CastRay(Vec(5, 15), 0.0, w.Segments(), 100.0)->range, 5.0, 1e-12);
  double total = 0.0;
  for (const Segment& s : w.Segments()) total += s.length();
  EXPECT_NEAR(total, 120 + 40 - 2 - 4 + 2 + 4, 1e-9);
}

}  // namespace
}  // namespace minenav
