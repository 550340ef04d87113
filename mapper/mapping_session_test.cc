#include "mapper/mapping_session.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/angle.h"
#include "mapper/test_world.h"

namespace minenav::mapper {
namespace {

using testing::DriftingOdometry;
using testing::MakeScan;
using testing::NoisySmallRoomScan;
using testing::ScanSpec;
using testing::SmallRoomWorld;

const std::vector<Pose2> kStations = {{3, 9, 0.3},      {9, 9.5, -0.5},   {17, 9, 2.0},
                                      {17.5, 2, 1.0},   {9.5, 1.5, -2.5}, {2.5, 2, 0.8}};

// A dense drive along the room: a pose every 0.25 m, turning slowly.
std::vector<Pose2> DenseDrive() {
  std::vector<Pose2> out;
  for (int k = 0; k <= 40; ++k) out.emplace_back(3.0 + 0.25 * k, 9.0 - 0.05 * k, 0.2 - 0.01 * k);
  return out;
}

TEST(MappingSessionTest, OptionsAreValidated) {
  MappingSessionOptions o;
  EXPECT_EQ(ValidateOptions(o), "");
  o.insert_min_translation = -1;
  EXPECT_NE(ValidateOptions(o).find("insert_min_translation"), std::string::npos);
  o = {};
  o.insert_min_rotation = std::nan("");
  EXPECT_NE(ValidateOptions(o).find("insert_min_rotation"), std::string::npos);
  o = {};
  o.refine_every_inserts = -2;
  EXPECT_NE(ValidateOptions(o).find("refine_every_inserts"), std::string::npos);
  o = {};
  o.mapper.grid_cell_size = 0;
  EXPECT_NE(ValidateOptions(o).find("grid_cell_size"), std::string::npos);
}

// Defaults insert every scan, each from odometry motion composed onto the last accepted
// scan's estimate: exactly what a hand-written loop over ContourMapper gives (the batch
// tool before the session existed), bit for bit.
TEST(MappingSessionTest, DefaultsInsertEveryScanChainingOdometry) {
  const std::vector<Pose2> odo = DriftingOdometry(kStations);
  MappingSession session;
  ContourMapper reference;
  std::optional<std::pair<Pose2, Pose2>> last;
  for (size_t k = 0; k < kStations.size(); ++k) {
    const LadarScan scan = NoisySmallRoomScan(kStations[k], static_cast<unsigned>(k + 1), 1'000'000 * static_cast<int64_t>(k + 1));
    const ScanResult r = session.AddScan(scan, odo[k]);
    ASSERT_EQ(r.outcome, ScanOutcome::kInserted) << "scan " << k << ": " << r.status;
    EXPECT_EQ(r.scan_index, static_cast<int>(k));
    const Pose2 initial = last ? last->first * Between(last->second, odo[k]) : odo[k];
    const InsertResult ref = reference.InsertScan(scan, initial);
    ASSERT_TRUE(ref.accepted);
    last = std::make_pair(ref.pose, odo[k]);
    EXPECT_EQ(r.initial.x, initial.x);
    EXPECT_EQ(r.pose.x, ref.pose.x);
    EXPECT_EQ(r.pose.y, ref.pose.y);
    EXPECT_EQ(r.pose.theta, ref.pose.theta);
    // And the estimate is right: the odometry drift (2 % and 0.23 deg per step) is removed.
    EXPECT_LT(TranslationDistance(r.pose, kStations[k]), 0.02) << k;
    EXPECT_LT(HeadingDistance(r.pose, kStations[k]), DegToRad(0.2)) << k;
  }
  EXPECT_EQ(session.state().inserted, 6);
  EXPECT_EQ(session.state().tracked, 0);
  ASSERT_EQ(session.Poses().size(), 6u);
  EXPECT_EQ(session.Poses()[3].utime, 4'000'000);
  EXPECT_EQ(session.map().NumContours(), reference.map().NumContours());
}

// A robot scanning while it moves: with insert_min_translation 1 m only about one scan per
// metre goes into the map, the others are tracked and still reported with good poses.
TEST(MappingSessionTest, InsertsOnlyAfterEnoughMotionAndTracksTheRest) {
  const std::vector<Pose2> truth = DenseDrive();
  const std::vector<Pose2> odo = DriftingOdometry(truth);
  MappingSessionOptions o;
  o.insert_min_translation = 1.0;
  o.insert_min_rotation = DegToRad(30.0);
  MappingSession session(o);
  Pose2 last_inserted;
  int inserted = 0, tracked = 0;
  for (size_t k = 0; k < truth.size(); ++k) {
    const ScanResult r = session.AddScan(NoisySmallRoomScan(truth[k], static_cast<unsigned>(k + 1), static_cast<int64_t>(k + 1)), odo[k]);
    ASSERT_TRUE(r.accepted()) << "scan " << k << ": " << r.status;
    if (r.outcome == ScanOutcome::kInserted) {
      ++inserted;
      if (k > 0) {
        EXPECT_GE(TranslationDistance(last_inserted, r.initial), 1.0);
      }
      last_inserted = r.pose;
    } else {
      ++tracked;
      EXPECT_LT(TranslationDistance(last_inserted, r.initial), 1.0);
      EXPECT_EQ(r.scan_index, -1);
    }
    EXPECT_LT(TranslationDistance(r.pose, truth[k]), 0.02) << k << " " << ToString(r.outcome);
    EXPECT_LT(HeadingDistance(r.pose, truth[k]), DegToRad(0.3)) << k;
  }
  // 10 m driven at 0.25 m per scan (odometry says 2 % more): one insert per 4 scans.
  EXPECT_EQ(inserted, 11);
  EXPECT_EQ(tracked, 30);
  EXPECT_EQ(static_cast<int>(session.mapper().scans().size()), inserted);
  EXPECT_EQ(session.Poses().size(), truth.size());  // every accepted scan has a pose row
}

TEST(MappingSessionTest, RefinesEveryNInsertsAndKeepsTheAnchorOnTheRefinedPose) {
  const std::vector<Pose2> odo = DriftingOdometry(kStations);
  MappingSessionOptions o;
  o.refine_every_inserts = 2;
  o.mapper.refinement.max_rounds = 2;
  MappingSession session(o);
  for (size_t k = 0; k < 4; ++k) {
    const ScanResult r = session.AddScan(NoisySmallRoomScan(kStations[k], static_cast<unsigned>(k + 1), static_cast<int64_t>(k)), odo[k]);
    ASSERT_EQ(r.outcome, ScanOutcome::kInserted) << r.status;
    EXPECT_EQ(r.refined, k % 2 == 1) << k;
    if (r.refined) {
      EXPECT_GE(r.refinement.total_error.size(), 1u);
    }
    EXPECT_EQ(session.state().anchor_pose.x, session.mapper().scans().back().pose.x);
    EXPECT_LT(TranslationDistance(r.pose, kStations[k]), 0.02);
  }
  EXPECT_EQ(session.state().inserts_since_refine, 0);
}

// A stop request during the periodic refinement (the live mapper told to stop while a scan
// is being refined): the refinement returns at once, the scan stays inserted, the poses are
// those before the refinement, and the refinement is still due (a checkpoint of this state
// resumes with it).
TEST(MappingSessionTest, AStoppedPeriodicRefinementLeavesTheScanInsertedAndStillDue) {
  const std::vector<Pose2> odo = DriftingOdometry(kStations);
  bool stop = false;
  int asked_while_stopping = 0;
  MappingSessionOptions o;
  o.refine_every_inserts = 3;
  o.mapper.refinement.max_rounds = 2;
  o.mapper.refinement.should_stop = [&] {
    asked_while_stopping += stop ? 1 : 0;
    return stop;
  };
  MappingSession session(o);
  for (size_t k = 0; k < 3; ++k) {
    stop = k == 2;  // the third insert triggers the refinement, and the stop is requested
    const ScanResult r = session.AddScan(NoisySmallRoomScan(kStations[k], static_cast<unsigned>(k + 1), static_cast<int64_t>(k)), odo[k]);
    ASSERT_EQ(r.outcome, ScanOutcome::kInserted) << r.status;
    EXPECT_EQ(r.refined, k == 2);
    if (k == 2) {
      EXPECT_TRUE(r.refinement.stopped) << r.refinement.reason;
      EXPECT_EQ(asked_while_stopping, 1);  // returned on the first question after the request
      EXPECT_EQ(r.refinement.rounds, 0);
      EXPECT_LT(TranslationDistance(r.pose, kStations[k]), 0.02);
    }
  }
  EXPECT_EQ(session.mapper().scans().size(), 3u);
  EXPECT_EQ(session.state().inserts_since_refine, 3);
  // Without the request it runs and counts as done.
  EXPECT_FALSE(session.Refine({}).stopped);
  EXPECT_EQ(session.state().inserts_since_refine, 0);
}

TEST(MappingSessionTest, RefusesBadScansLeavesTheMapAndGoesOn) {
  const std::vector<Pose2> odo = DriftingOdometry(kStations);
  MappingSession session;
  for (size_t k = 0; k < 3; ++k)
    ASSERT_TRUE(session.AddScan(NoisySmallRoomScan(kStations[k], static_cast<unsigned>(k + 1), static_cast<int64_t>(k)), odo[k])
                    .accepted());
  const ContourMap before = session.map();
  const MappingSessionState state_before = session.state();
  auto unchanged = [&] {
    ASSERT_EQ(session.map().NumContours(), before.NumContours());
    for (const auto& [id, c] : before.contours()) EXPECT_EQ(session.map().Get(id).points, c.points);
    EXPECT_EQ(session.mapper().scans().size(), 3u);
    EXPECT_EQ(session.state().anchor_pose.x, state_before.anchor_pose.x);
    EXPECT_EQ(session.state().poses.size(), 3u);
  };
  // Overlaps nothing: a scan of another room, odometry saying it is far away.
  LadarScan far = MakeScan(testing::Rectangle(100, 100, 104, 103), Pose2(102, 101, 0));
  far.utime = 10;
  ScanResult r = session.AddScan(far, Pose2(102, 101, 0));
  EXPECT_EQ(r.outcome, ScanOutcome::kRefused);
  EXPECT_NE(r.status.find("overlap"), std::string::npos) << r.status;
  unchanged();
  // A wildly wrong initial estimate: odometry 120 degrees and metres off.
  r = session.AddScan(NoisySmallRoomScan(Pose2(10, 6, 0), 20, 11), odo[2] * Pose2(-6, 3, 2.1));
  EXPECT_EQ(r.outcome, ScanOutcome::kRefused) << r.status;
  unchanged();
  // All points out of range.
  LadarScan blank = NoisySmallRoomScan(kStations[3], 21, 12);
  for (float& v : blank.ranges) v = 1000.0f;
  r = session.AddScan(blank, odo[3]);
  EXPECT_EQ(r.outcome, ScanOutcome::kRefused);
  EXPECT_NE(r.status.find("too few usable points"), std::string::npos) << r.status;
  unchanged();
  // A malformed scan and a non-finite odometry pose.
  LadarScan bad = NoisySmallRoomScan(kStations[3], 22, 13);
  bad.angle_step = 0;
  r = session.AddScan(bad, odo[3]);
  EXPECT_NE(r.status.find("invalid scan"), std::string::npos) << r.status;
  r = session.AddScan(NoisySmallRoomScan(kStations[3], 23, 14), Pose2(std::nan(""), 0, 0));
  EXPECT_NE(r.status.find("not finite"), std::string::npos) << r.status;
  unchanged();
  EXPECT_EQ(session.state().refused, 5);
  // A scan with a hole still goes in; the session goes on.
  LadarScan holey = NoisySmallRoomScan(kStations[3], 24, 15);
  for (size_t i = 100; i < 300; ++i) holey.ranges[i] = std::nanf("");
  r = session.AddScan(holey, odo[3]);
  EXPECT_EQ(r.outcome, ScanOutcome::kInserted) << r.status;
  EXPECT_LT(TranslationDistance(r.pose, kStations[3]), 0.02);
}

// --load-map: the first scan is localised against the loaded contours (not taken at its
// odometry pose), then the map keeps growing from there.
TEST(MappingSessionTest, StartsFromALoadedMap) {
  MappingSession session({}, testing::SmallRoomContours());
  const int before = session.map().NumContours();
  const Pose2 truth(9, 9.5, -0.5);
  const ScanResult r = session.AddScan(NoisySmallRoomScan(truth, 3, 1), Pose2(9.25, 9.3, -0.45));
  ASSERT_EQ(r.outcome, ScanOutcome::kInserted) << r.status;
  EXPECT_LT(TranslationDistance(r.pose, truth), 0.02);
  EXPECT_LT(HeadingDistance(r.pose, truth), DegToRad(0.2));
  EXPECT_GE(session.map().NumContours(), before);
  // Off the map entirely: refused, nothing inserted.
  MappingSession other({}, testing::SmallRoomContours());
  LadarScan far = MakeScan(testing::Rectangle(100, 100, 104, 103), Pose2(102, 101, 0));
  EXPECT_EQ(other.AddScan(far, Pose2(102, 101, 0)).outcome, ScanOutcome::kRefused);
  EXPECT_TRUE(other.mapper().scans().empty());
}

}  // namespace
}  // namespace minenav::mapper
