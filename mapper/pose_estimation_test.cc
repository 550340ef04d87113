#include "mapper/pose_estimation.h"

#include <gtest/gtest.h>

#include "mapper/line_search.h"
#include "mapper/test_world.h"

namespace minenav::mapper {
namespace {

using testing::MakeScan;
using testing::ScanSpec;
using testing::SmallRoomContours;
using testing::SmallRoomWorld;

TEST(LineSearchTest, FindsTheMinimumOfAParabola) {
  const auto ls = LineSearch([](double l) { return (l - 0.37) * (l - 0.37); }, 0.37 * 0.37, 3.0, 1e-6);
  EXPECT_NEAR(ls.lambda, 0.37, 2e-6);
  EXPECT_LT(ls.evaluations, 60);
  const auto none = LineSearch([](double l) { return 1.0 + l; }, 1.0, 3.0, 1e-6);
  EXPECT_EQ(none.lambda, 0.0);
}

TEST(LineSearchTest, QuadraticSearchIsExactOnAParabola) {
  auto f = [](double l) { return 2.0 * (l - 0.37) * (l - 0.37) + 1.0; };
  const auto ls = QuadraticLineSearch(f, f(0), -4.0 * 0.37, 3.0, 1e-6);
  EXPECT_NEAR(ls.lambda, 0.37, 1e-12);
  EXPECT_EQ(ls.evaluations, 2);
  // Minimum beyond the bound: clamped to λ_max.
  EXPECT_NEAR(QuadraticLineSearch(f, f(0), -4.0 * 0.37, 0.2, 1e-6).lambda, 0.2, 1e-12);
  // Not a parabola: still descends, to near the minimum at (pi - 0.1) / 3.
  auto g = [](double l) { return std::cos(3.0 * l + 0.1); };
  const auto fb = QuadraticLineSearch(g, g(0), -3.0 * std::sin(0.1), 2.09, 1e-6);
  EXPECT_LT(fb.value, -0.95);
  // Rising everywhere within the bound: the fallback finds no step.
  auto h = [](double l) { return l * l * l - 0.001 * l; };
  EXPECT_LT(QuadraticLineSearch(h, h(0), -0.001, 1.0, 1e-6).value, 0.0);
}

TEST(PoseEstimationTest, OptionsAreValidated) {
  PoseEstimationOptions o;
  EXPECT_EQ(ValidateOptions(o), "");
  o.final_threshold = 5;
  EXPECT_NE(ValidateOptions(o), "");
}

TEST(PoseEstimationTest, TrueMapZeroErrorAtTruth) {
  const ContourMap map = SmallRoomContours();
  const Pose2 truth(9.0, 8.5, 0.2);
  const PreprocessedScan scan = PreprocessScan(MakeScan(SmallRoomWorld(), truth), {});
  const ScanFit fit = MeasureScanFit(scan, truth, map, 0.1);
  EXPECT_LT(fit.MeanSquaredDistance(), 1e-10);  // ranges are floats: ~1e-6 m
  EXPECT_GT(fit.MatchedFraction(), 0.95);
}

struct Case {
  Pose2 truth, start;
};

class PoseEstimationRecovers : public ::testing::TestWithParam<Case> {};

TEST_P(PoseEstimationRecovers, ExactScan) {
  const ContourMap map = SmallRoomContours();
  const Case c = GetParam();
  const PreprocessedScan scan = PreprocessScan(MakeScan(SmallRoomWorld(), c.truth), {});
  const PoseEstimationResult r = EstimatePose(scan, c.start, map);
  EXPECT_TRUE(r.converged) << r.status;
  EXPECT_LT(TranslationDistance(r.pose, c.truth), 1e-3) << r.pose << " " << r.status << " it " << r.iterations;
  EXPECT_LT(HeadingDistance(r.pose, c.truth), DegToRad(0.01));
}

INSTANTIATE_TEST_SUITE_P(Starts, PoseEstimationRecovers,
                         ::testing::Values(Case{{9.0, 8.5, 0.2}, {9.3, 8.2, 0.25}},
                                           Case{{3.0, 2.0, -1.0}, {2.5, 2.6, -0.92}},
                                           Case{{17.0, 9.0, 2.5}, {16.6, 9.4, 2.56}},
                                           Case{{10.0, 1.5, 0.0}, {10.2, 1.3, -0.06}}));

TEST(PoseEstimationTest, NoisyScanWithinACentimetre) {
  const ContourMap map = SmallRoomContours();
  const Pose2 truth(9.0, 8.5, 0.2);
  ScanSpec spec;
  spec.range_sigma = 0.03;
  spec.num_points = 2048;
  const PreprocessedScan scan = PreprocessScan(MakeScan(SmallRoomWorld(), truth, spec), {});
  const PoseEstimationResult r = EstimatePose(scan, Pose2(9.33, 8.2, 0.2 + DegToRad(3.3)), map);
  EXPECT_LT(TranslationDistance(r.pose, truth), 0.01) << r.pose << " " << r.status;
  EXPECT_LT(HeadingDistance(r.pose, truth), DegToRad(0.1));
  EXPECT_GT(r.fit.MatchedFraction(), 0.9);
}

TEST(PoseEstimationTest, HeadingSearchWidensTheBasinForLaggingOdometry) {
  // A 180° SICK-like scan started 12–30° off in heading with a tight first threshold, as
  // tracking a continuously scanning robot uses: points 10 m away start 2–5 m from their
  // walls. With the heading search (±32°) every start recovers the truth; the thesis
  // descent alone (search off) loses at least one of them.
  const ContourMap map = SmallRoomContours();
  const Pose2 truth(4.0, 9.5, -0.4);
  ScanSpec spec;
  spec.num_points = 720;
  LadarScan full = MakeScan(SmallRoomWorld(), truth, spec);
  for (size_t i = 0; i < full.ranges.size(); ++i)  // keep the front half: a 180° scanner
    if (std::abs(full.Bearing(i)) > kPi / 2.0) full.ranges[i] = std::nanf("");
  const PreprocessedScan scan = PreprocessScan(full, {});
  PoseEstimationOptions plain;
  plain.initial_threshold = 0.5;
  plain.final_threshold = 0.05;
  PoseEstimationOptions searching = plain;
  searching.heading_search_range = DegToRad(32.0);
  ASSERT_EQ(ValidateOptions(searching), "");
  int plain_lost = 0;
  for (const double error_deg : {12.0, -18.0, 24.0, -30.0}) {
    const Pose2 start(truth.x + 0.05, truth.y - 0.05, truth.theta + DegToRad(error_deg));
    const Pose2 seeded = SearchHeading(scan, start, map, searching);
    EXPECT_LT(HeadingDistance(seeded, truth), DegToRad(3.0)) << error_deg << " deg: " << seeded;
    const PoseEstimationResult r = EstimatePose(scan, start, map, searching);
    EXPECT_LT(TranslationDistance(r.pose, truth), 1e-3) << error_deg << " deg: " << r.pose << " " << r.status;
    EXPECT_LT(HeadingDistance(r.pose, truth), DegToRad(0.01)) << error_deg << " deg";
    if (HeadingDistance(EstimatePose(scan, start, map, plain).pose, truth) > DegToRad(1.0)) ++plain_lost;
  }
  EXPECT_GE(plain_lost, 1) << "the thesis descent alone should lose a start this far off";
  // Started at the truth, the search changes nothing (the initial heading's fit wins).
  const PoseEstimationResult at_truth = EstimatePose(scan, truth, map, searching);
  EXPECT_LT(TranslationDistance(at_truth.pose, truth), 1e-3);
  EXPECT_LT(HeadingDistance(at_truth.pose, truth), DegToRad(0.01));
  // Off: SearchHeading returns the start; bad values are refused.
  EXPECT_EQ(SearchHeading(scan, Pose2(4, 9, 0.3), map, plain).theta, 0.3);
  searching.heading_search_step = 0.0;
  EXPECT_NE(ValidateOptions(searching), "");
}

TEST(PoseEstimationTest, NoOverlapIsReportedNotGuessed) {
  const ContourMap map = SmallRoomContours();
  // A scan of a different room far away: nothing corresponds.
  const PreprocessedScan scan =
      PreprocessScan(MakeScan(testing::Rectangle(100, 100, 104, 103), Pose2(102, 101, 0)), {});
  const PoseEstimationResult r = EstimatePose(scan, Pose2(102, 101, 0), map);
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.status.find("too few correspondences"), std::string::npos) << r.status;
}

}  // namespace
}  // namespace minenav::mapper
