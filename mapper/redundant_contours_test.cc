#include "mapper/redundant_contours.h"

#include <gtest/gtest.h>

namespace minenav::mapper {
namespace {

TEST(RedundantContoursTest, RemovesTheNewerCopyOfAWallAndKeepsTheRest) {
  ContourMap map;
  const int old_wall = map.Create(ResamplePolyline({{0, 0}, {10, 0}}, false, 0.5));
  // A newer copy 0.2 m off, overlapping x in [6, 10], continuing to x = 14 where it is new.
  const int copy = map.Create(ResamplePolyline({{6, 0.2}, {14, 0.2}}, false, 0.5));
  // The other side of a thin wall (faces the other way) must stay.
  const int back = map.Create(ResamplePolyline({{10, -0.1}, {0, -0.1}}, false, 0.5));
  const int removed = RemoveRedundantContours(map);
  EXPECT_GT(removed, 5);
  EXPECT_TRUE(map.Find(old_wall));
  EXPECT_TRUE(map.Find(back));
  EXPECT_FALSE(map.Find(copy));
  // The part of the copy beyond the old wall survives as a contour of its own.
  bool found = false;
  for (const auto& [id, c] : map.contours())
    if (id != old_wall && id != back) {
      found = true;
      for (const auto& p : c.points) EXPECT_GT(p.x(), 10.0);
      EXPECT_NEAR(c.points.back().x(), 14.0, 1e-9);
    }
  EXPECT_TRUE(found);
  EXPECT_EQ(RemoveRedundantContours(map), 0);
}

TEST(RedundantContoursTest, APostBesideAWallIsNotACopyOfIt) {
  ContourMap map;
  // A post 0.3 m square standing 0.3 m in front of a wall (free space y > 0): its front face
  // faces the same way as the wall and lies within the distance, but it is short.
  map.Create(ResamplePolyline({{0, 0}, {10, 0}}, false, 0.5));
  map.Create({{5.3, 0.3}, {5.3, 0.6}, {5.0, 0.6}, {5.0, 0.3}}, true);
  const int wall_later = map.Create(ResamplePolyline({{10, 0}, {12, 0}}, false, 0.5));
  EXPECT_EQ(RemoveRedundantContours(map), 0);
  EXPECT_EQ(map.NumContours(), 3);
  EXPECT_TRUE(map.Find(wall_later));
}

}  // namespace
}  // namespace minenav::mapper
