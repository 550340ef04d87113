// SupervisorNode on a fake bus and a clock the test owns, with real (tiny) child processes:
// readiness from HEARTBEATs on the bus, the supervisor's own HEARTBEAT, a bad heartbeat
// counted, the stop.

#include "fleet/supervisor_node.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "common/node/fake_runtime.h"
#include "minenav/heartbeat_t.hpp"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

constexpr int64_t kT0 = 1'700'000'000'000'000;

FleetSpec Fleet(const std::string& text, const std::string& out) {
  FleetSpec fleet = ParseFleetFile(text, "t.fleet", {{"OUT", out}, {"BIN", "/b"}, {"FLEET_DIR", "/f"}}, {});
  for (ProcessSpec& p : fleet.processes) p.argv[0] = "/bin/" + p.argv[0];
  return fleet;
}

heartbeat_t Heartbeat(const std::string& process, int8_t state, int64_t utime) {
  heartbeat_t h{};
  h.utime = utime;
  h.process = process;
  h.pid = 4242;
  h.state = state;
  return h;
}

class SupervisorNodeTest : public ::testing::Test {
 protected:
  // Spins the node for `seconds` of the test's clock in 20 ms steps, real time passing
  // alongside so the children can run and exit.
  void Spin(double seconds) {
    for (int k = 0; k < static_cast<int>(seconds / 0.02); ++k) {
      clock_.Advance(20'000);
      fake_.runtime().SpinOnce(0);
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  }
  // The message of the supervisor's last HEARTBEAT.
  heartbeat_t LastOwnHeartbeat() {
    const auto all = fake_.bus().Decoded<heartbeat_t>("HEARTBEAT");
    for (auto it = all.rbegin(); it != all.rend(); ++it)
      if (it->process == "fleet") return *it;
    return heartbeat_t{};
  }

  testing::TempDir dir_{"supervisor_node"};
  ManualClock clock_{kT0};
  FakeRuntime fake_{clock_, /*heartbeat_period=*/0.5, "fleet"};
};

TEST_F(SupervisorNodeTest, HeartbeatsOnTheBusMakeAProcessReadyThenTheStopEndsEveryProcess) {
  SupervisorOptions options;
  options.out = dir_.path().string();
  options.status_period = 0;
  options.stop_grace = 1;
  SupervisorNode node(fake_.runtime(),
                      Fleet("[process a]\ncommand = sleep 1000\ngroup = g\nheartbeat = fake_a\nready = ok\n"
                            "[process b]\ncommand = sleep 1000\ngroup = g\nafter = a\nheartbeat = none\n",
                            options.out),
                      options);
  Spin(1.0);
  EXPECT_EQ(LastOwnHeartbeat().message, "1 waiting, 1 starting") << "b waits for a's OK";
  fake_.bus().InjectMessage("HEARTBEAT", Heartbeat("fake_a", heartbeat_t::WARN, clock_.NowUtime()));
  Spin(1.0);
  EXPECT_EQ(LastOwnHeartbeat().message, "1 waiting, 1 starting") << "WARN is not OK";
  fake_.bus().InjectMessage("HEARTBEAT", Heartbeat("fake_a", heartbeat_t::OK, clock_.NowUtime()));
  Spin(1.0);
  EXPECT_EQ(LastOwnHeartbeat().message, "2 running");
  EXPECT_EQ(LastOwnHeartbeat().state, heartbeat_t::OK);

  // A heartbeat of no known state is counted as bad, never taken.
  fake_.bus().InjectMessage("HEARTBEAT", Heartbeat("fake_a", 9, clock_.NowUtime()));
  Spin(0.6);
  EXPECT_EQ(LastOwnHeartbeat().messages_bad, 1);

  const auto t0 = std::chrono::steady_clock::now();
  fake_.runtime().Shutdown();  // what SIGINT leads to: StopFleet
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 0.9)
      << "sleep exits on SIGINT at once: no need for the grace period";
  const heartbeat_t last = LastOwnHeartbeat();
  EXPECT_EQ(last.state, heartbeat_t::STOPPING);
  EXPECT_EQ(last.message, "2 stopped");
}

TEST_F(SupervisorNodeTest, ACrashLoopTurnsTheSupervisorsHeartbeatToWarnAndSaysWho) {
  SupervisorOptions options;
  options.out = dir_.path().string();
  options.status_period = 0;
  options.restart.backoff_initial = 0.05;
  options.restart.crash_loop_failures = 3;
  SupervisorNode node(fake_.runtime(), Fleet("[process crash]\ncommand = false\ngroup = g\nheartbeat = none\n"
                                             "[process steady]\ncommand = sleep 1000\ngroup = g\nheartbeat = none\n",
                                             options.out),
                      options);
  Spin(3.0);
  const heartbeat_t h = LastOwnHeartbeat();
  EXPECT_EQ(h.state, heartbeat_t::WARN);
  EXPECT_EQ(h.message, "1 running, 1 given up; crash given up");
  fake_.runtime().Shutdown();
}

}  // namespace
}  // namespace minenav
