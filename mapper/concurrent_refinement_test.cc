#include "mapper/concurrent_refinement.h"

#include <gtest/gtest.h>

#include "mapper/map_evaluation.h"
#include "mapper/map_expansion.h"
#include "mapper/test_world.h"

namespace minenav::mapper {
namespace {

using testing::LoopStations;
using testing::LoopWorld;
using testing::MakeScan;
using testing::ScanSpec;

double MaxPoseError(const std::vector<MappedScan>& scans, const std::vector<Pose2>& truth, double* max_heading) {
  double worst = 0, worst_h = 0;
  for (size_t k = 0; k < scans.size(); ++k) {
    worst = std::max(worst, TranslationDistance(scans[k].pose, truth[k]));
    worst_h = std::max(worst_h, HeadingDistance(scans[k].pose, truth[k]));
  }
  *max_heading = worst_h;
  return worst;
}

TEST(ConcurrentRefinementTest, OptionsAreValidated) {
  ConcurrentRefinementOptions o;
  o.max_rounds = 8;
  EXPECT_EQ(ValidateOptions(o), "");
  o.max_rounds = 0;
  EXPECT_NE(ValidateOptions(o), "");
}

TEST(ConcurrentRefinementTest, ClosesALoopBuiltFromDriftingPoses) {
  // Scans around a loop placed at dead-reckoned poses whose error grows along the loop;
  // the map is built from them as they are (expansion + fitting, no pose estimation), so
  // the last scans disagree with the first where the loop meets.
  const std::vector<Pose2> truth = LoopStations();
  std::vector<MappedScan> scans;
  ContourMap map;
  Pose2 drift;  // accumulated dead-reckoning error, applied in the vehicle frame
  for (size_t k = 0; k < truth.size(); ++k) {
    if (k > 0) drift = drift * Pose2(0.02, 0.015, DegToRad(0.25));
    ScanSpec spec;
    spec.num_points = 720;
    spec.max_range = 9.0;
    spec.range_sigma = 0.01;
    spec.seed = static_cast<unsigned>(k + 1);
    MappedScan s{PreprocessScan(MakeScan(LoopWorld(), truth[k], spec), {}), truth[k] * drift, k == 0};
    scans.push_back(std::move(s));
    const MapExpansionResult ex = ExpandMap(scans.back().scan, scans.back().pose, map);
    FitContours(map.Ids(), scans, map);
  }
  double h_before = 0, h_after = 0;
  const double before = MaxPoseError(scans, truth, &h_before);
  ConcurrentRefinementOptions o;
  o.max_rounds = 8;
  const ConcurrentRefinementResult r = RefineConcurrently(scans, map, o);
  const double after = MaxPoseError(scans, truth, &h_after);
  ASSERT_GE(r.total_error.size(), 2u) << r.reason;
  EXPECT_LT(r.total_error.back(), r.total_error.front());
  EXPECT_GT(before, 0.15);
  EXPECT_LT(after, 0.6 * before) << "pose error " << before << " -> " << after << " m, heading "
                                 << RadToDeg(h_before) << " -> " << RadToDeg(h_after) << " deg, rounds " << r.rounds
                                 << " (" << r.reason << ")";
  EXPECT_LT(h_after, 0.4 * h_before);  // measured: 0.225 -> 0.119 m, 2.25 -> 0.69 deg in 8 rounds
}

}  // namespace
}  // namespace minenav::mapper
