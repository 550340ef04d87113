#include "mapper/contour_fitting.h"

#include <gtest/gtest.h>

#include "evaluation/map_evaluation.h"
#include "mapper/map_expansion.h"
#include "mapper/test_world.h"

namespace minenav::mapper {
namespace {

using testing::MakeScan;
using testing::ScanSpec;
using testing::SmallRoomWorld;

std::vector<MappedScan> NoisyScans(const std::vector<Pose2>& poses, double sigma) {
  std::vector<MappedScan> out;
  unsigned seed = 11;
  for (const Pose2& p : poses) {
    ScanSpec spec;
    spec.num_points = 2048;
    spec.range_sigma = sigma;
    spec.seed = seed++;
    out.push_back({PreprocessScan(MakeScan(SmallRoomWorld(), p, spec), {}), p, false});
  }
  return out;
}

TEST(ContourFittingTest, OptionsAreValidated) {
  ContourFittingOptions o;
  EXPECT_EQ(ValidateOptions(o), "");
  o.damping = 0;
  EXPECT_NE(ValidateOptions(o), "");
}

TEST(ContourFittingTest, DisplacedContourReturnsToExactScans) {
  // The true room contour shifted 8 cm inwards (and rotated a little) must move back.
  const std::vector<MappedScan> scans = NoisyScans({{3, 9, 0}, {17, 2, 1}, {10, 10, -2}}, 0.0);
  ContourMap map = testing::SmallRoomContours();
  const int room = map.Ids()[0];
  std::vector<Eigen::Vector2d> moved = map.Get(room).points;
  for (auto& p : moved) p = Eigen::Vector2d(10, 6) + 0.992 * (p - Eigen::Vector2d(10, 6)) + Eigen::Vector2d(0.03, -0.02);
  map.SetPoints(room, moved);
  const auto before = ContourDeviation(map, SmallRoomWorld());
  const ContourFittingResult r = FitContours({room}, scans, map);
  const auto after = ContourDeviation(map, SmallRoomWorld());
  EXPECT_LT(r.error_after, 0.01 * r.error_before) << r.reason;
  EXPECT_GT(before.mean, 0.03);
  EXPECT_LT(after.mean, 0.002) << r.reason << " after " << r.iterations;
}

TEST(ContourFittingTest, RoughContoursFromNoisyScansGetCloserToTheWalls) {
  // Map expansion from the first of three noisy scans gives a rough fit through noisy scan
  // points; fitting to all three averages the noise out.
  const std::vector<MappedScan> scans = NoisyScans({{3, 9, 0}, {17, 2, 1}, {10, 10, -2}}, 0.03);
  ContourMap map;
  const MapExpansionResult ex = ExpandMap(scans[0].scan, scans[0].pose, map);
  // Resample to the nominal length so every vertex is free to move.
  for (const int id : ex.Touched()) map.Resample(id, 0.5);
  const auto before = ContourDeviation(map, SmallRoomWorld());
  const ContourFittingResult r = FitContours(map.Ids(), scans, map);
  const auto after = ContourDeviation(map, SmallRoomWorld());
  EXPECT_LT(r.error_after, r.error_before);
  EXPECT_LT(after.mean, 0.7 * before.mean) << before.mean << " -> " << after.mean << " " << r.reason;
  EXPECT_LT(after.mean, 0.02);
}

TEST(ContourFittingTest, PlainGradientAlsoDescends) {
  const std::vector<MappedScan> scans = NoisyScans({{3, 9, 0}, {17, 2, 1}}, 0.0);
  ContourMap map = testing::SmallRoomContours();
  const int room = map.Ids()[0];
  std::vector<Eigen::Vector2d> moved = map.Get(room).points;
  for (auto& p : moved) p += Eigen::Vector2d(0.05, 0.05);
  map.SetPoints(room, moved);
  ContourFittingOptions o;
  o.precondition = false;
  o.max_iterations = 100;
  const ContourFittingResult r = FitContours({room}, scans, map, o);
  EXPECT_LT(r.error_after, 0.5 * r.error_before) << r.reason;
}

TEST(ContourFittingTest, DegenerateSegmentsAreRemovedAndTinyContoursLeftAlone) {
  const std::vector<MappedScan> scans = NoisyScans({{3, 9, 0}}, 0.0);
  ContourMap map;
  const int a = map.Create({{1, 0}, {3, 0}, {3.02, 0}, {5, 0}, {7, 0}});
  const int single = map.Create({{19.99, 2}, {19.99, 8}});  // one segment: not fitted
  const ContourFittingResult r = FitContours({a, single}, scans, map);
  EXPECT_EQ(r.vertices_removed, 1);
  EXPECT_EQ(map.Get(single).points[0], Eigen::Vector2d(19.99, 2));
  for (const auto& p : map.Get(a).points) EXPECT_NEAR(p.y(), 0.0, 1e-3);
}

}  // namespace
}  // namespace minenav::mapper
