// The estimators' shared node, driven through the fake bus: pairing, the initial-estimate
// rules, what is published for an estimate and for a skipped scan, HEARTBEAT status.

#include "common/node/scan_estimation_node.h"

#include <gtest/gtest.h>

#include "common/node/conversions.h"
#include "common/node/fake_runtime.h"
#include "minenav/heartbeat_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/pose_estimate_t.hpp"

namespace minenav {
namespace {

constexpr int64_t kT0 = 1'700'000'000'000'000;

LadarScan Scan(int64_t id) {
  LadarScan s;
  s.utime = kT0 + id * 100'000;
  s.scan_id = id;
  s.angle_step = 0.1f;
  s.min_range = 0.5f;
  s.max_range = 30.0f;
  s.ranges.assign(10, 5.0f);
  return s;
}

odometry_t Odometry(int64_t utime, double x) {
  OdometryReading o;
  o.utime = utime;
  o.pose = Pose2(x, 0.0, 0.0);
  return ToLcm(o);
}

struct Harness {
  explicit Harness(const std::string& initial) {
    runtime->SpinOnce(0);  // starts the clock: the first heartbeat
    options.initial = initial;
    options.pose_channel = "POSE_TEST";
  }
  void Feed(int64_t id, double odometry_x) {
    bus->InjectMessage("ODOMETRY", Odometry(kT0 + id * 100'000, odometry_x));
    bus->InjectMessage("LADAR_SCAN", ToLcm(Scan(id)));
    bus->HandleFor(0);
  }
  ManualClock clock{kT0};
  FakeRuntime fake{clock, /*heartbeat_period=*/1.0, "test_estimator"};
  FakeBus* bus = &fake.bus();
  NodeRuntime* runtime = &fake.runtime();
  ScanEstimationOptions options;
};

// The estimator under test says the vehicle is 0.5 m ahead of the initial estimate.
std::optional<MatchResult> HalfMetreAhead(const LadarScan&, const Pose2& initial, std::string*) {
  MatchResult e;
  e.pose = initial * Pose2(0.5, 0.0, 0.0);
  e.converged = true;
  e.status = "ok";
  return e;
}

TEST(ScanEstimationNodeTest, ChainedInitialEstimatesCarryTheCorrectionForward) {
  Harness h("chained");
  std::vector<Pose2> initials;
  ScanEstimationNode node(*h.runtime, h.options, "test", [&](const LadarScan& s, const Pose2& initial, std::string* why) {
    initials.push_back(initial);
    return HalfMetreAhead(s, initial, why);
  });
  h.Feed(0, 0.0);
  h.Feed(1, 1.0);
  h.Feed(2, 2.0);
  ASSERT_EQ(initials.size(), 3u);
  EXPECT_NEAR(initials[0].x, 0.0, 1e-12);  // no trusted estimate yet: the odometry
  EXPECT_NEAR(initials[1].x, 1.5, 1e-12);  // 0.5 (estimate) + 1.0 (odometry since)
  EXPECT_NEAR(initials[2].x, 3.0, 1e-12);
  const auto poses = h.bus->Decoded<pose_estimate_t>("POSE_TEST");
  ASSERT_EQ(poses.size(), 3u);
  EXPECT_EQ(poses[2].scan_id, 2);
  EXPECT_EQ(poses[2].utime, Scan(2).utime);
  EXPECT_EQ(poses[2].source, "test");
  EXPECT_NEAR(poses[2].pose.x, 3.5, 1e-12);
  EXPECT_TRUE(poses[2].converged);
  EXPECT_GE(poses[2].compute_time, 0.0f);
  EXPECT_EQ(node.scans_converged(), 3);
}

TEST(ScanEstimationNodeTest, OdometryInitialEstimatesIgnoreEarlierEstimates) {
  Harness h("odometry");
  std::vector<Pose2> initials;
  ScanEstimationNode node(*h.runtime, h.options, "test", [&](const LadarScan& s, const Pose2& initial, std::string* why) {
    initials.push_back(initial);
    return HalfMetreAhead(s, initial, why);
  });
  h.Feed(0, 0.0);
  h.Feed(1, 1.0);
  ASSERT_EQ(initials.size(), 2u);
  EXPECT_NEAR(initials[1].x, 1.0, 1e-12);
}

TEST(ScanEstimationNodeTest, ASkippedScanIsCountedAndShownInTheHeartbeat) {
  Harness h("chained");
  ScanEstimationNode node(*h.runtime, h.options, "test", [](const LadarScan&, const Pose2&, std::string* why) {
    *why = "no map yet";
    return std::optional<MatchResult>();
  });
  h.Feed(0, 0.0);
  EXPECT_TRUE(h.bus->PublishedOn("POSE_TEST").empty());
  EXPECT_EQ(node.scans_skipped(), 1);
  EXPECT_EQ(node.scans_estimated(), 0);
  h.clock.Advance(1'000'000);
  h.runtime->SpinOnce(0);  // the next heartbeat carries the node's status
  const auto hb = h.bus->Decoded<heartbeat_t>("HEARTBEAT");
  ASSERT_EQ(hb.size(), 2u);
  EXPECT_EQ(hb[0].state, heartbeat_t::OK);
  EXPECT_EQ(hb[1].state, heartbeat_t::WARN);
  EXPECT_EQ(hb[1].message, "no map yet");
}

TEST(ScanEstimationNodeTest, PosesOutNeedsBatchMode) {
  Harness h("odometry");
  h.options.poses_out = "/tmp/never_written.csv";
  EXPECT_THROW(ScanEstimationNode(*h.runtime, h.options, "test", HalfMetreAhead), UsageError);
}

}  // namespace
}  // namespace minenav
