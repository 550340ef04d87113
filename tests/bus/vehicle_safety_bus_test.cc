// vehicle_sim's safety limits on a real LCM bus, inside a private network namespace
// (tests/bus/private_net.sh sets MINENAV_IN_PRIVATE_NET and LCM_DEFAULT_URL):
//   - issue 11: one DRIVE_COMMAND with timeout = 1e9, then silence (a sender that died or a
//     lost link), must not drive the vehicle for ever: it stops at its own stale limit
//     (--command-timeout), whichever of the two is shorter (lcmtypes/drive_command_t.lcm).

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "common/node/bus.h"
#include "common/node/lcm_bus.h"
#include "minenav/drive_command_t.hpp"
#include "minenav/vehicle_truth_t.hpp"
#include "tests/bus/private_bus_test.h"
#include "tests/child_process.h"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

using testing::ChildProcess;
using testing::ReadTextFile;

using VehicleSafetyBusTest = testing::PrivateBusTest;

TEST_F(VehicleSafetyBusTest, OneCommandWithAHugeTimeoutStopsAtTheVehiclesStaleLimit) {
  testing::TempDir dir("minenav_vehicle_safety_test");
  constexpr double kStaleLimit = 0.5;  // s, vehicle_sim --command-timeout
  constexpr double kRate = 20.0;       // Hz, vehicle_sim --rate: one tick is 0.05 s
  constexpr double kSpeed = 1.0;       // m/s, commanded and allowed
  // Instant acceleration and braking, so the stop comes exactly at the first stale tick.
  ChildProcess sim({MINENAV_VEHICLE_SIM_BIN, "--run-for", "90", "--generate", "mine", "--seed", "3", "--rate", "20",
                    "--command-timeout", "0.5", "--max-forward-speed", "1", "--max-acceleration", "0",
                    "--max-deceleration", "0"},
                   dir / "sim.txt");
  LcmBus bus(url_, 10000);
  std::vector<vehicle_truth_t> truth;
  Subscribe<vehicle_truth_t>(bus, "SIM_TRUTH", [&](const vehicle_truth_t& m) { truth.push_back(m); });
  ASSERT_TRUE(Pump(bus, 20.0, [&] { return truth.size() >= 5; }))
      << "no SIM_TRUTH within 20 s\nsim: " << ReadTextFile(dir / "sim.txt");
  const size_t before = truth.size();

  drive_command_t forever{};
  forever.utime = 1;
  forever.seq = 1;
  forever.mode = drive_command_t::VELOCITY;
  forever.v = kSpeed;
  forever.omega = 0.0;
  forever.timeout = 1e9;  // "valid for 31 years"
  ASSERT_TRUE(Publish(bus, "DRIVE_COMMAND", forever));
  // Silence: 3 s, six times the stale limit.
  Pump(bus, 3.0);
  EXPECT_TRUE(sim.Running()) << ReadTextFile(dir / "sim.txt");
  sim.Signal(SIGTERM);
  EXPECT_EQ(sim.Wait(10.0), 0) << ReadTextFile(dir / "sim.txt");

  // The samples after the command: it moved, then stopped for good.
  std::vector<vehicle_truth_t> after(truth.begin() + static_cast<std::ptrdiff_t>(before), truth.end());
  ASSERT_GT(after.size(), 20u) << "SIM_TRUTH stopped flowing";
  size_t first_moving = after.size(), last_moving = after.size();
  for (size_t i = 0; i < after.size(); ++i) {
    if (std::abs(after[i].v) > 0.0) {
      if (first_moving == after.size()) first_moving = i;
      last_moving = i;
    }
  }
  ASSERT_LT(first_moving, after.size()) << "the vehicle never moved: the command was lost?\n"
                                        << ReadTextFile(dir / "sim.txt");
  // Ticks are stamped with vehicle_sim's clock, the same clock that timed the command's
  // receipt: every moving tick is at most the stale limit after the receipt, and the
  // receipt precedes the first moving tick.
  const double moving_s = static_cast<double>(after[last_moving].utime - after[first_moving].utime) * 1e-6;
  EXPECT_LE(moving_s, kStaleLimit + 1e-6) << "still driving " << moving_s << " s after the command";
  ASSERT_LT(last_moving + 1, after.size()) << "still driving at the end of the 3 s of silence";
  // The first moving tick integrates at most one tick before the receipt (more if the
  // process was held up: the tick is capped at 1 s, so allow a held-up tick of 0.1 s).
  const double distance = std::hypot(after.back().pose.x - after[first_moving].pose.x,
                                     after.back().pose.y - after[first_moving].pose.y);
  EXPECT_LE(distance, kSpeed * (kStaleLimit + 1.0 / kRate + 0.1)) << "drove " << distance << " m";
  // ...and it drove for the stale limit, not a shorter time (two ticks short nominally;
  // half the limit leaves room for a machine so loaded that a tick comes late).
  EXPECT_GE(distance, kSpeed * kStaleLimit / 2) << "stopped too early: " << distance << " m";
  // Stopped, it stays put: no motion in the samples after the stop.
  for (size_t i = last_moving + 1; i < after.size(); ++i) {
    EXPECT_EQ(after[i].v, 0.0) << "sample " << i;
    EXPECT_EQ(after[i].pose.x, after[last_moving + 1].pose.x) << "sample " << i;
    EXPECT_EQ(after[i].pose.y, after[last_moving + 1].pose.y) << "sample " << i;
  }
  // At least 2 s of standing still were observed.
  EXPECT_GE(static_cast<double>(after.back().utime - after[last_moving].utime) * 1e-6, 2.0);
}

}  // namespace
}  // namespace minenav
