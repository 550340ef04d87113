#include "evaluation/map_evaluation.h"

#include <gtest/gtest.h>

namespace minenav::mapper {
namespace {

TEST(MapEvaluationTest, DeviationAndCoverageOfAShiftedWall) {
  const std::vector<Segment> truth = {Segment(0, 0, 10, 0)};
  ContourMap map;
  map.Create({{0, 0.1}, {5, 0.1}, {10, 0.3}});
  const MapDeviation d = ContourDeviation(map, truth, 0.01);
  EXPECT_NEAR(d.max, 0.3, 1e-9);
  EXPECT_NEAR(d.mean, 0.5 * 0.1 + 0.5 * 0.2, 2e-3);  // 0.1 on the first half, 0.1..0.3 on the second
  const std::vector<Eigen::Vector2d> pts = {{1, 0}, {4, 0}, {9, 0}, {50, 0}};
  EXPECT_DOUBLE_EQ(Coverage(pts, map, 0.15), 0.5);
}

}  // namespace
}  // namespace minenav::mapper
