// The feature-based estimator live on the bus (runs inside tests/bus/private_net.sh):
// vehicle_sim (the indoor mockup, odometry with a gyro bias) + ladar_driver (Cyclone) +
// feature_pose_estimator taking the map from LINE_MAP. Every POSE_FPE is compared with
// SIM_TRUTH at the scan's utime.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <thread>

#include "common/angle.h"
#include "common/node/bus.h"
#include "common/node/conversions.h"
#include "common/node/lcm_bus.h"
#include "minenav/heartbeat_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "minenav/vehicle_truth_t.hpp"
#include "tests/child_process.h"
#include "tests/temp_dir.h"
#include "tests/bus/private_bus_test.h"

namespace minenav {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using minenav::testing::ChildProcess;
using minenav::testing::ReadTextFile;

using FeaturePoseEstimatorBus = testing::PrivateBusTest;

TEST_F(FeaturePoseEstimatorBus, PoseFpeFollowsSimTruthWhileOdometryDrifts) {
  const char* url_env = url_.c_str();
  const std::string url = url_env;
  testing::TempDir dir("minenav_fpe_bus_test");

  // The vehicle stands at the first station of Table 1; its gyro drifts 0.3 deg/s, so the
  // odometry heading (the initial estimate) walks away from the truth.
  ChildProcess fpe({MINENAV_FPE_BIN, "--heartbeat-period", "0.2"}, dir / "fpe.txt");
  ChildProcess ladar({MINENAV_LADAR_DRIVER_BIN, "--sensor", "cyclone", "--min-range", "0.5", "--seed", "7"},
                     dir / "ladar.txt");
  ChildProcess sim({MINENAV_VEHICLE_SIM_BIN, "--generate", "mockup", "--seed", "2",
                    "--odometry-heading-drift-per-second", "0.005", "--map-period", "0.5"},
                   dir / "sim.txt");

  LcmBus bus(url, 1000);
  std::deque<TruthReading> truth;
  std::vector<PoseEstimate> estimates;
  std::vector<double> odometry_heading_error;
  bool fpe_heartbeat = false;
  Subscribe<vehicle_truth_t>(bus, "SIM_TRUTH", [&](const vehicle_truth_t& m) { truth.push_back(FromLcm(m)); });
  Subscribe<odometry_t>(bus, "ODOMETRY", [&](const odometry_t& m) {
    const OdometryReading o = FromLcm(m);
    if (!truth.empty()) odometry_heading_error.push_back(HeadingDistance(o.pose, truth.back().pose));
  });
  Subscribe<pose_estimate_t>(bus, "POSE_FPE", [&](const pose_estimate_t& m) { estimates.push_back(FromLcm(m)); });
  Subscribe<heartbeat_t>(bus, "HEARTBEAT", [&](const heartbeat_t& m) {
    fpe_heartbeat = fpe_heartbeat || std::string(m.process) == "feature_pose_estimator";
  });
  const auto end = Clock::now() + std::chrono::seconds(30);
  while (Clock::now() < end && estimates.size() < 25) bus.HandleFor(10'000);

  fpe.Signal(SIGTERM);
  ladar.Signal(SIGTERM);
  sim.Signal(SIGTERM);
  EXPECT_EQ(fpe.Wait(10.0), 0) << ReadTextFile(dir / "fpe.txt");
  EXPECT_EQ(ladar.Wait(10.0), 0) << ReadTextFile(dir / "ladar.txt");
  EXPECT_EQ(sim.Wait(10.0), 0) << ReadTextFile(dir / "sim.txt");

  ASSERT_GE(estimates.size(), 25u) << "fpe: " << ReadTextFile(dir / "fpe.txt") << "\nladar: " << ReadTextFile(dir / "ladar.txt");
  EXPECT_TRUE(fpe_heartbeat);
  int converged = 0;
  for (const PoseEstimate& e : estimates) {
    EXPECT_EQ(e.source, "fpe");
    if (!e.converged) continue;
    ++converged;
    // Truth at the scan's utime (SIM_TRUTH at 20 Hz; the vehicle stands still).
    const TruthReading* nearest = nullptr;
    for (const TruthReading& t : truth) {
      if (!nearest || std::llabs(t.utime - e.utime) < std::llabs(nearest->utime - e.utime)) nearest = &t;
    }
    ASSERT_NE(nearest, nullptr);
    EXPECT_LT(TranslationDistance(e.pose, nearest->pose), 0.05) << "scan " << e.scan_id;
    EXPECT_LT(HeadingDistance(e.pose, nearest->pose), DegToRad(0.5)) << "scan " << e.scan_id;
  }
  EXPECT_GE(converged, 23) << ReadTextFile(dir / "fpe.txt");
  // The odometry was really off by the end, and the estimates were not.
  ASSERT_FALSE(odometry_heading_error.empty());
  EXPECT_GT(odometry_heading_error.back(), DegToRad(1.0));
}

}  // namespace
}  // namespace minenav
