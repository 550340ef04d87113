// Signed command channels on a real LCM bus (issue 16, "Security"; common/node/auth_bus.h),
// inside a private network namespace (tests/bus/private_net.sh):
//   1. vehicle_sim runs with a key file; this test drives it with signed DRIVE_COMMANDs for
//      a second (it moves: the test can fail) while command_attacker listens and captures them;
//   2. the vehicle stops (its command timeout), then command_attacker floods DRIVE_COMMAND for
//      3 s with replays of what it captured, forgeries under another key, tampered copies and
//      unsigned commands: SIM_TRUTH must show the vehicle not moving at all, and vehicle_sim's
//      HEARTBEAT must count the refusals (messages_bad) and say why;
//   3. a signed sender moves it again: the flood locked nobody out.

#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <memory>
#include <string>
#include <vector>

#include "common/auth_key_file.h"
#include "common/clock.h"
#include "common/node/auth_bus.h"
#include "common/node/lcm_bus.h"
#include "minenav/drive_command_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/vehicle_truth_t.hpp"
#include "tests/bus/private_bus_test.h"
#include "tests/child_process.h"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

using testing::ChildProcess;
using testing::ReadTextFile;
using CommandAuthBusTest = testing::PrivateBusTest;

int64_t NowUtime() { return WallClock().NowUtime(); }

// Distance travelled between the first and last SIM_TRUTH samples stamped in [from, to], and
// the largest |v| among them.
struct Motion {
  int samples = 0;
  double distance = 0.0;
  double max_speed = 0.0;
};
Motion MotionBetween(const std::vector<vehicle_truth_t>& truth, int64_t from, int64_t to) {
  Motion m;
  const vehicle_truth_t* first = nullptr;
  for (const vehicle_truth_t& t : truth) {
    if (t.utime < from || t.utime > to) continue;
    if (first == nullptr) first = &t;
    ++m.samples;
    m.max_speed = std::max(m.max_speed, std::abs(t.v));
    m.distance = std::max(m.distance, std::hypot(t.pose.x - first->pose.x, t.pose.y - first->pose.y));
  }
  return m;
}

TEST_F(CommandAuthBusTest, ForgedReplayedTamperedAndUnsignedCommandsNeverMoveTheVehicle) {
  testing::TempDir dir("minenav_command_auth_test");
  const std::string key_file = dir / "fleet.key";
  SaveAuthKeyFile(key_file, AuthKeyRing{{RandomAuthKey(1)}});
  // Instant acceleration and braking and a 0.3 s command timeout: motion shows at the first tick
  // after a command it accepts, and ends 0.3 s after the last one.
  ChildProcess sim({MINENAV_VEHICLE_SIM_BIN, "--run-for", "120", "--generate", "mine", "--seed", "3", "--rate", "20",
                    "--command-timeout", "0.3", "--max-forward-speed", "1", "--max-acceleration", "0",
                    "--max-deceleration", "0", "--auth.key-file", key_file},
                   dir / "sim.txt");
  WallClock clock;
  AuthOptions auth;
  auth.key_file = key_file;
  AuthBus bus(std::make_unique<LcmBus>(url_, 10000), auth, clock);
  std::vector<vehicle_truth_t> truth;
  heartbeat_t sim_heartbeat{};
  Subscribe<vehicle_truth_t>(bus, "SIM_TRUTH", [&](const vehicle_truth_t& m) { truth.push_back(m); });
  Subscribe<heartbeat_t>(bus, "HEARTBEAT", [&](const heartbeat_t& m) {
    if (m.process == "vehicle_sim") sim_heartbeat = m;
  });
  ASSERT_TRUE(Pump(bus, 20.0, [&] { return truth.size() >= 5 && sim_heartbeat.seq > 0; }))
      << "no SIM_TRUTH/HEARTBEAT within 20 s\nsim: " << ReadTextFile(dir / "sim.txt");
  const int64_t bad_before = sim_heartbeat.messages_bad;

  auto drive_signed = [&](double seconds) {
    const int64_t start = NowUtime();
    int64_t seq = 0;
    while (NowUtime() - start < static_cast<int64_t>(seconds * 1e6)) {
      drive_command_t d{};
      d.utime = NowUtime();
      d.seq = ++seq;
      d.mode = drive_command_t::VELOCITY;
      d.v = 0.5;
      d.timeout = 0.2;
      Publish(bus, "DRIVE_COMMAND", d);
      Pump(bus, 0.05);
    }
    return start;
  };

  // 1. The attacker listens for 3 s while a signed sender drives for 1 s.
  ChildProcess attacker({MINENAV_COMMAND_ATTACKER_BIN, "--channel", "DRIVE_COMMAND", "--capture", "3", "--attack", "3"}, dir / "attacker.txt");
  Pump(bus, 0.8);
  const int64_t drive1 = drive_signed(1.0);
  const Motion moved1 = MotionBetween(truth, drive1, NowUtime());
  EXPECT_GT(moved1.distance, 0.2) << "signed commands did not move the vehicle\n" << ReadTextFile(dir / "sim.txt");

  // 2. Stopped (timeout 0.3 s) before the attack starts (3 s after the attacker did).
  Pump(bus, 1.2);
  const int64_t attack_from = NowUtime();
  int64_t attack_to = attack_from;
  ASSERT_TRUE(Pump(bus, 15.0, [&] {
    if (attacker.Running()) attack_to = NowUtime();
    return !attacker.Running();
  })) << "command_attacker did not end";
  EXPECT_EQ(attacker.Wait(5.0), 0) << ReadTextFile(dir / "attacker.txt");
  const std::string attack_report = ReadTextFile(dir / "attacker.txt");
  EXPECT_NE(attack_report.find(" signed)"), std::string::npos) << attack_report;
  EXPECT_EQ(attack_report.find("(0 signed)"), std::string::npos) << "nothing captured to replay: " << attack_report;
  Pump(bus, 1.5);  // the heartbeat after the flood
  const Motion during = MotionBetween(truth, attack_from, NowUtime());
  EXPECT_GT(during.samples, 40) << "SIM_TRUTH stopped flowing during the attack";
  EXPECT_EQ(during.max_speed, 0.0) << "the vehicle moved on an attacker's command\n" << attack_report;
  EXPECT_EQ(during.distance, 0.0) << attack_report;
  const int64_t refused = sim_heartbeat.messages_bad - bad_before;
  EXPECT_GT(refused, 1000) << "vehicle_sim's HEARTBEAT counted " << refused << " refusals\n" << attack_report;
  std::printf("attack: %s vehicle_sim refused %lld, heartbeat: %s\n", attack_report.c_str(),
              static_cast<long long>(refused), sim_heartbeat.message.c_str());
  const std::string sim_log = ReadTextFile(dir / "sim.txt");
  for (const char* reason : {"replayed", "bad tag", "unsigned"})
    EXPECT_NE(sim_log.find(std::string("refused by authentication: ") + reason), std::string::npos)
        << reason << " not logged\n" << sim_log.substr(0, 4000);

  // 3. The key holder still drives it.
  const int64_t drive2 = drive_signed(1.0);
  EXPECT_GT(MotionBetween(truth, drive2, NowUtime()).distance, 0.2) << "locked out after the attack";
  EXPECT_LT(attack_to - attack_from, 10'000'000);
  sim.Signal(SIGTERM);
  EXPECT_EQ(sim.Wait(10.0), 0) << ReadTextFile(dir / "sim.txt");
}

}  // namespace
}  // namespace minenav
