// Every field of the iconic estimator's options is declared (issue 12): reachable by its
// key from a config file or the command line, and counted, so that a field added without a
// declaration fails here.

#include <gtest/gtest.h>

#include "common/config_testing.h"
#include "pose_estimator/iconic/correspondence.h"
#include "pose_estimator/iconic/iconic_estimator.h"
#include "pose_estimator/iconic/iconic_matcher.h"
#include "pose_estimator/iconic/multi_scan_matcher.h"
#include "pose_estimator/iconic/scan_polylines.h"
#include "pose_estimator/iconic/segment_map.h"

namespace minenav {
namespace {

TEST(IconicOptionsTest, EveryFieldOfEveryStructIsDeclaredAndReachable) {
  // IconicMatchOptions: thresholds (2), epsilons (2), iterations, correspondences, loss and
  // its scale, reject_open_ends, the two step limits.
  EXPECT_EQ(ExpectEveryOptionReachable<IconicMatchOptions>().size(), 11u);
  // CorrespondenceOptions: method, cell_size, max_distance.
  EXPECT_EQ(ExpectEveryOptionReachable<CorrespondenceOptions>().size(), 3u);
  // SegmentMapOptions: min_segment_length, duplicate_tolerance.
  EXPECT_EQ(ExpectEveryOptionReachable<SegmentMapOptions>().size(), 2u);
  // PartialScanOptions: break_distance, min_points. PolylineFitOptions: segment_length.
  EXPECT_EQ(ExpectEveryOptionReachable<PartialScanOptions>().size(), 2u);
  EXPECT_EQ(ExpectEveryOptionReachable<PolylineFitOptions>().size(), 1u);
  // MultiScanOptions: match (11) and partial (2) nested, and its own 6.
  EXPECT_EQ(ExpectEveryOptionReachable<MultiScanOptions>().size(), 11u + 2u + 6u);
  // IconicEstimatorOptions: match, correspondence, segment_map, partial and fit nested
  // (11 + 3 + 2 + 2 + 1), mode, scan_map_cell_size, chain_odometry, seed_simultaneous, and
  // the 5 it hands on to the simultaneous adjustment (max_pair_distance,
  // every_overlapping_scan, point_stride and the two epsilons) as simultaneous.*.
  EXPECT_EQ(ExpectEveryOptionReachable<IconicEstimatorOptions>().size(), 11u + 3u + 2u + 2u + 1u + 4u + 5u);
}

TEST(IconicOptionsTest, NestedStructsNestTheirKeys) {
  IconicEstimatorOptions o;
  ConfigSchema schema("test", "nested keys");
  DeclareOptions(OptionScope(schema), o);
  schema.LoadText(
      "mode = all-previous\nmatch.min_threshold = 0.15\nmatch.loss = huber\ncorrespondence.method = grid\n"
      "segment_map.min_segment_length = 0.01\npartial.break_distance = 0.7\nfit.segment_length = 0.4\n"
      "simultaneous.point_stride = 3\n",
      "test");
  EXPECT_EQ(o.mode, IconicMode::kAllPrevious);
  EXPECT_DOUBLE_EQ(o.match.min_threshold, 0.15);
  EXPECT_EQ(o.match.loss, RobustLoss::kHuber);
  EXPECT_EQ(o.correspondence.method, CorrespondenceMethod::kGridSearch);
  EXPECT_DOUBLE_EQ(o.map.min_segment_length, 0.01);
  EXPECT_DOUBLE_EQ(o.partial.break_distance, 0.7);
  EXPECT_DOUBLE_EQ(o.fit.segment_length, 0.4);
  EXPECT_EQ(o.point_stride, 3);
  EXPECT_THROW(schema.LoadText("match.max_iterations = 0", "test"), UsageError);
}

}  // namespace
}  // namespace minenav
