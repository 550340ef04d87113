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

}  // namespace
}  // namespace minenav::mapper
