// Every field of the feature-based estimator's options is declared (issue 12): reachable by
// its key from a config file or the command line, and counted, so that a field added
// without a declaration fails here.

#include <gtest/gtest.h>

#include "common/config_testing.h"
#include "pose_estimator/feature/feature_pose_estimator.h"

namespace minenav {
namespace {

TEST(FeatureOptionsTest, EveryFieldOfEveryStructIsDeclaredAndReachable) {
  EXPECT_EQ(ExpectEveryOptionReachable<FeatureMapOptions>().size(), 1u);  // vertex_merge_distance
  // PredictionOptions: max_range, min_line_length, collinear_angle.
  EXPECT_EQ(ExpectEveryOptionReachable<PredictionOptions>().size(), 3u);
  // CornerOperatorOptions: arm_length, min_arm_points, min_arm_extent, min/max_corner_angle,
  // max_arm_rms, min_arm_to_ray_angle, min_corner_separation.
  EXPECT_EQ(ExpectEveryOptionReachable<CornerOperatorOptions>().size(), 8u);
  // ExtractionOptions: 12 of its own and corner (8) nested.
  EXPECT_EQ(ExpectEveryOptionReachable<ExtractionOptions>().size(), 12u + 8u);
  // MatchingOptions: the six thesis tolerances and max_search_nodes.
  EXPECT_EQ(ExpectEveryOptionReachable<MatchingOptions>().size(), 7u);
  // MinimizationOptions: 13 fields.
  EXPECT_EQ(ExpectEveryOptionReachable<MinimizationOptions>().size(), 13u);
  // FeaturePoseEstimatorOptions: the five nested structs (1 + 3 + 20 + 7 + 13) and min_matches,
  // measure_range_noise, range_noise_floor, min_support, support_distance,
  // max_median_distance_factor; stage_clock (a function the program passes, not a parameter) is
  // the one field not declared.
  EXPECT_EQ(ExpectEveryOptionReachable<FeaturePoseEstimatorOptions>().size(), 1u + 3u + 20u + 7u + 13u + 6u);
}

TEST(FeatureOptionsTest, NestedStructsNestTheirKeys) {
  FeaturePoseEstimatorOptions o;
  ConfigSchema schema("test", "nested keys");
  DeclareOptions(OptionScope(schema), o);
  schema.LoadText(
      "extraction.corner.arm_length = 0.6\nmatching.angerr = 45deg\nfeature_map.vertex_merge_distance = 0.02\n",
      "test");
  EXPECT_DOUBLE_EQ(o.extraction.corner.arm_length, 0.6);
  EXPECT_NEAR(o.matching.angerr, DegToRad(45.0), 1e-12);
  EXPECT_DOUBLE_EQ(o.map.vertex_merge_distance, 0.02);
  EXPECT_THROW(schema.LoadText("matching.angerr = 2", "test"), UsageError);  // beyond 1.5 rad
}

}  // namespace
}  // namespace minenav
