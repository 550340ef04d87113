#include "mapper/concurrent_refinement.h"

#include <gtest/gtest.h>

#include "evaluation/map_evaluation.h"
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

// Scans around a loop placed at dead-reckoned poses whose error grows along the loop; the
// map is built from them as they are (expansion + fitting, no pose estimation), so the last
// scans disagree with the first where the loop meets.
std::vector<MappedScan> BuildDriftedLoop(int num_points, double max_range, double sigma, ContourMap& map,
                                         double* before, double* before_h) {
  const std::vector<Pose2> truth = LoopStations();
  std::vector<MappedScan> scans;
  Pose2 drift;
  for (size_t k = 0; k < truth.size(); ++k) {
    if (k > 0) drift = drift * Pose2(0.02, 0.015, DegToRad(0.25));
    ScanSpec spec;
    spec.num_points = num_points;
    spec.max_range = max_range;
    spec.range_sigma = sigma;
    spec.seed = static_cast<unsigned>(k + 1);
    scans.push_back({PreprocessScan(MakeScan(LoopWorld(), truth[k], spec), {}), truth[k] * drift, k == 0});
    ExpandMap(scans.back().scan, scans.back().pose, map);
    FitContours(map.Ids(), scans, map);
  }
  *before = MaxPoseError(scans, truth, before_h);
  return scans;
}

// With the pose-graph step (loop_closure.h) the loop closes in one call: 1440-point scans
// to 15 m, so neighbouring scans share enough walls and cribs for direct registration.
TEST(ConcurrentRefinementTest, PoseGraphClosesTheLoop) {
  ContourMap map;
  double before = 0, h_before = 0, h_after = 0;
  std::vector<MappedScan> scans = BuildDriftedLoop(1440, 15.0, 0.02, map, &before, &h_before);
  ConcurrentRefinementOptions o;
  o.max_rounds = 4;
  o.loop_closure.max_pair_distance = 15.0;
  const ConcurrentRefinementResult r = RefineConcurrently(scans, map, o);
  const double after = MaxPoseError(scans, LoopStations(), &h_after);
  EXPECT_TRUE(r.loop_closure.applied) << r.loop_closure.reason;
  EXPECT_GT(before, 0.2);
  // Measured: 0.225 -> 0.062 m, 2.25 -> 0.25 deg (the alternation alone, below: 0.76 deg).
  EXPECT_LT(after, 0.08) << "pose error " << before << " -> " << after << " m, heading " << RadToDeg(h_before) << " -> "
                         << RadToDeg(h_after) << " deg (" << r.loop_closure.reason << "; " << r.reason << ")";
  EXPECT_LT(h_after, DegToRad(0.4));
}

// The thesis's alternation alone (no pose graph) on sparser scans (720 points to 9 m): it
// lowers the total error and turns the loop's headings back, slowly; along the feature-poor
// corridors its positions do not come back (measured 0.225 -> 0.317 m, 2.25 -> 0.76 deg in 8
// rounds). On these sparse scans direct registration slides along the corridors too, which
// is why the pose-graph test above uses denser, longer scans.
TEST(ConcurrentRefinementTest, AlternationAloneClosesALoopPartly) {
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
  o.loop_closure.enabled = false;
  const ConcurrentRefinementResult r = RefineConcurrently(scans, map, o);
  const double after = MaxPoseError(scans, truth, &h_after);
  ASSERT_GE(r.total_error.size(), 2u) << r.reason;
  EXPECT_LT(r.total_error.back(), r.total_error.front());
  EXPECT_GT(before, 0.15);
  EXPECT_LT(after, 1.6 * before) << "pose error " << before << " -> " << after << " m, rounds " << r.rounds;
  EXPECT_LT(h_after, 0.4 * h_before) << "heading " << RadToDeg(h_before) << " -> " << RadToDeg(h_after) << " deg, rounds "
                                     << r.rounds << " (" << r.reason << ")";
}

// Issue 11, item 12: a stop request (the node hands NodeRuntime::StopSignalled) must end a
// long refinement at once. The stop test says yes from its n-th question on; the refinement
// must return on that very question, report stopped, and leave poses and map as after its
// last kept step: as they were when it stops in the pose-graph step, with the closed loop
// and no half-done round when it stops in round 1.
TEST(ConcurrentRefinementTest, AStopRequestEndsItAtOnceLeavingTheMapConsistent) {
  ContourMap map;
  double before = 0, h_before = 0;
  const std::vector<MappedScan> start = BuildDriftedLoop(1440, 15.0, 0.02, map, &before, &h_before);
  const ContourMap start_map = map;
  const double start_error = TotalError(start, start_map, 0.2);
  // Questions asked by an uninterrupted run: one per registration, pose-graph pass, scan
  // measured and scan refined, so no step between two is longer than one of those.
  ConcurrentRefinementOptions o;
  o.max_rounds = 4;
  o.loop_closure.max_pair_distance = 15.0;
  int questions = 0, questions_in_loop_closure = 0, registrations = 0;
  o.should_stop = [&] {
    ++questions;
    return false;
  };
  {
    std::vector<MappedScan> scans = start;
    ContourMap m = start_map;
    const ConcurrentRefinementResult full = RefineConcurrently(scans, m, o);
    EXPECT_FALSE(full.stopped);
    ASSERT_TRUE(full.loop_closure.applied) << full.loop_closure.reason;
    ASSERT_GE(full.rounds, 1) << full.reason;
    const int n = static_cast<int>(scans.size());
    registrations = full.loop_closure.pairs_tried;
    // Measured: 132 questions, 29 of them registrations, in 1.1 s.
    EXPECT_GE(questions, n + registrations + 1 + n + full.rounds * 2 * n);
    // Up to the first round: the total error (one per scan), the registrations, at most
    // max_gate_passes passes, one before applying, the error after the closure.
    questions_in_loop_closure = n + registrations + o.loop_closure.max_gate_passes + 1 + n;
  }
  // A round asks 2n questions (one before it, one per free scan, one per scan measured).
  for (const int stop_at : {1, 2, 10 + registrations / 2, questions_in_loop_closure + 3}) {
    std::vector<MappedScan> scans = start;
    ContourMap m = start_map;
    int asked = 0, asked_after_yes = 0;
    o.should_stop = [&] {
      ++asked;
      if (asked > stop_at) ++asked_after_yes;
      return asked >= stop_at;
    };
    const ConcurrentRefinementResult r = RefineConcurrently(scans, m, o);
    EXPECT_TRUE(r.stopped) << stop_at << ": " << r.reason;
    EXPECT_EQ(asked_after_yes, 0) << stop_at << ": asked again after the stop request";
    EXPECT_NE(r.reason.find("stopped"), std::string::npos) << r.reason;
    EXPECT_EQ(r.rounds, 0);
    if (stop_at > questions_in_loop_closure) {
      // In round 1: the closed loop is kept, the round under way undone.
      EXPECT_TRUE(r.loop_closure.applied) << stop_at << ": " << r.loop_closure.reason;
      EXPECT_LT(TotalError(scans, m, 0.2), start_error);
      double h_after = 0;
      EXPECT_LT(MaxPoseError(scans, LoopStations(), &h_after), 0.08);
      continue;
    }
    EXPECT_FALSE(r.loop_closure.applied);
    for (size_t k = 0; k < scans.size(); ++k) {
      EXPECT_EQ(scans[k].pose.x, start[k].pose.x) << stop_at << " scan " << k;
      EXPECT_EQ(scans[k].pose.theta, start[k].pose.theta) << stop_at << " scan " << k;
    }
    ASSERT_EQ(m.NumContours(), start_map.NumContours()) << stop_at;
    for (const auto& [id, c] : start_map.contours()) EXPECT_EQ(m.Get(id).points, c.points) << stop_at;
  }
}

}  // namespace
}  // namespace minenav::mapper
