// A world that changes while the fleet runs (issue 6, thesis 4.8), live on the LCM bus
// inside a private network namespace (tests/bus/private_net.sh sets
// MINENAV_IN_PRIVATE_NET and LCM_DEFAULT_URL on a port of its own):
//   - vehicle_sim --world A --world B --world-change-at T with ladar_driver taking its
//     world from SIM_WORLD: every scan is the exact ray cast of A or of B from the true
//     pose, the switch happens where vehicle_sim says it changed the world, and two scans
//     from the same pose differ exactly at the readings where A and B differ.

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>

#include "common/file_io.h"
#include "common/node/bus.h"
#include "common/node/conversions.h"
#include "common/node/lcm_bus.h"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/vehicle_truth_t.hpp"
#include "tests/changing_world_fixtures.h"
#include "tests/child_process.h"
#include "tests/temp_dir.h"
#include "tests/bus/private_bus_test.h"

namespace minenav {
namespace {

namespace fs = std::filesystem;
using testing::ChildProcess;
using testing::Logged;
using testing::ReadTextFile;

using ChangingWorldBusTest = testing::PrivateBusTest;

TEST_F(ChangingWorldBusTest, TheLadarCastsTheNewWorldFromTheMomentVehicleSimChangesIt) {
  testing::TempDir dir("minenav_changing_world_bus");
  const std::string a = dir / "closed.json", b = dir / "open.json";
  SaveSegmentsJson(a, testing::DoorClosedRoom());
  SaveSegmentsJson(b, testing::DoorOpenRoomWithBox());
  constexpr double kChangeAt = 3.0;  // s after vehicle_sim's first tick

  LcmBus bus(url_, 10000);
  std::vector<Logged<ladar_scan_t>> scans;
  std::vector<line_map_t> worlds;
  std::vector<vehicle_truth_t> truth;
  Subscribe<ladar_scan_t>(bus, "LADAR_SCAN", [&](const ladar_scan_t& m) { scans.push_back({0, m}); });
  Subscribe<line_map_t>(bus, "SIM_WORLD", [&](const line_map_t& m) { worlds.push_back(m); });
  Subscribe<vehicle_truth_t>(bus, "SIM_TRUTH", [&](const vehicle_truth_t& m) { truth.push_back(m); });

  // The ladar first (it takes its world from SIM_WORLD); processes stop by themselves
  // after 60 s should the test die.
  ChildProcess ladar({MINENAV_LADAR_DRIVER_BIN, "--run-for", "60", "--points", "1024", "--range-sigma", "0",
                      "--range-resolution", "0", "--mixed-pixel-probability", "0", "--beam-divergence", "0"},
                     dir / "ladar.txt");
  ChildProcess sim({MINENAV_VEHICLE_SIM_BIN, "--run-for", "60", "--world", a, "--world", b, "--world-change-at",
                    "3", "--start-pose", "0,0,0"},
                   dir / "sim.txt");
  // Until 20 scans stamped after the second world went out have arrived.
  const auto done = [&] {
    int64_t changed = -1;
    for (const auto& w : worlds)
      if (SegmentsFromLcm(w).size() == testing::DoorOpenRoomWithBox().size()) {
        changed = w.utime;
        break;
      }
    if (changed < 0) return false;
    int n = 0;
    for (const auto& s : scans) n += s.msg.utime > changed ? 1 : 0;
    return n >= 20;
  };
  ASSERT_TRUE(Pump(bus, 30.0, done)) << scans.size() << " scans\nladar: " << ReadTextFile(dir / "ladar.txt")
                                     << "\nsim: " << ReadTextFile(dir / "sim.txt");
  sim.Signal(SIGTERM);
  ladar.Signal(SIGTERM);
  EXPECT_EQ(sim.Wait(10.0), 0) << ReadTextFile(dir / "sim.txt");
  EXPECT_EQ(ladar.Wait(10.0), 0) << ReadTextFile(dir / "ladar.txt");

  // The change, as vehicle_sim published it: the first SIM_WORLD with B's segments, about
  // kChangeAt after its first SIM_WORLD (both are stamped with vehicle_sim's clock).
  ASSERT_GE(worlds.size(), 2u);
  int64_t change_utime = -1;
  for (const auto& w : worlds)
    if (SegmentsFromLcm(w).size() == testing::DoorOpenRoomWithBox().size()) {
      change_utime = w.utime;
      break;
    }
  ASSERT_GT(change_utime, 0) << "no SIM_WORLD with the second world";
  EXPECT_NEAR(static_cast<double>(change_utime - worlds.front().utime) * 1e-6, kChangeAt, 0.2);
  // The truth sample just before the change: scans later than it are cast in B.
  int64_t before_change = -1;
  for (const auto& t : truth)
    if (t.utime < change_utime) before_change = std::max(before_change, t.utime);
  ASSERT_GT(before_change, 0);

  const testing::WorldMatch match =
      testing::MatchScans(scans, Pose2(), testing::DoorClosedRoom(), testing::DoorOpenRoomWithBox(), 1e-4);
  size_t first_after = scans.size();
  int before = 0, after = 0;
  for (size_t k = 0; k < scans.size(); ++k) {
    const int64_t u = scans[k].msg.utime;
    ASSERT_NE(match.world[k], -1) << "scan " << k << " is neither world";
    EXPECT_EQ(match.world[k], u > before_change ? 1 : 0)
        << "scan " << k << " at " << u - change_utime << " us from the change";
    if (match.world[k] == 1) {
      first_after = std::min(first_after, k);
      ++after;
    } else {
      ++before;
    }
  }
  EXPECT_GE(before, 10);
  EXPECT_GE(after, 20);
  ASSERT_GT(first_after, 0u);
  ASSERT_LT(first_after, scans.size());
  // Same pose before and after: they differ exactly where the world did.
  const ladar_scan_t& p = scans.front().msg;
  const ladar_scan_t& q = scans.back().msg;
  const auto differ = testing::DifferingReadings(p, q, 1e-3);
  EXPECT_EQ(differ, testing::DifferingRayCasts(p, Pose2(), testing::DoorClosedRoom(), testing::DoorOpenRoomWithBox(),
                                               1e-3));
  EXPECT_GT(differ.size(), 100u);
}

}  // namespace
}  // namespace minenav
