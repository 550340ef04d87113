#include "fleet/supervisor.h"

#include <gtest/gtest.h>

#include <csignal>

#include "fleet/status_table.h"

namespace minenav {
namespace {

constexpr int64_t kS = 1'000'000;
constexpr int64_t kT0 = 1'700'000'000 * kS;

FleetSpec Fleet(const std::string& text) {
  return ParseFleetFile(text, "t.fleet", {{"OUT", "/o"}, {"BIN", "/b"}, {"FLEET_DIR", "/f"}}, {});
}

RestartOptions FastRestarts() {
  RestartOptions o;
  o.backoff_initial = 0.5;
  o.backoff_max = 4.0;
  o.stable_after = 10.0;
  o.crash_loop_failures = 4;
  o.crash_loop_window = 30.0;
  return o;
}

std::vector<size_t> Starts(const std::vector<SupervisorAction>& actions) {
  std::vector<size_t> out;
  for (const SupervisorAction& a : actions)
    if (a.kind == SupervisorAction::Kind::kStart) out.push_back(a.process);
  return out;
}

HeartbeatSample Heartbeat(const std::string& process, int pid, HeartbeatState state, int64_t received,
                          int64_t messages_in = 0) {
  HeartbeatSample s;
  s.process = process;
  s.pid = pid;
  s.state = state;
  s.received = received;
  s.utime = received;
  s.messages_in = messages_in;
  return s;
}

// A fake supervisor loop: the test plays the processes and the clock.
constexpr const char* kChain = R"(
[process sim]
command = /b/vehicle_sim
group = vehicle
ready = heartbeat

[process ladar]
command = /b/ladar_driver
group = vehicle
after = sim
ready = ok

[process mapper]
command = /b/contour_mapper
group = vehicle
after = ladar

[process logger]
command = lcm-logger
group = base
heartbeat = none
)";

TEST(Supervisor, StartsInOrderOnceWhatEachWaitsForIsReady) {
  Supervisor sup(Fleet(kChain), FastRestarts());
  int64_t now = kT0;
  EXPECT_EQ(Starts(sup.Tick(now)), (std::vector<size_t>{0, 3})) << "sim and logger wait for nothing";
  sup.OnStarted(0, 100, now);
  sup.OnStarted(3, 103, now);
  EXPECT_TRUE(Starts(sup.Tick(now + kS / 10)).empty()) << "ladar waits for sim's heartbeat";
  EXPECT_EQ(sup.Status(now)[1].state_text, "waiting for sim");

  // A heartbeat from before sim's start does not count; one in WARN does (ready = heartbeat).
  sup.OnHeartbeat(Heartbeat("vehicle_sim", 99, HeartbeatState::kOk, now - 1));
  EXPECT_TRUE(Starts(sup.Tick(now + kS / 5)).empty());
  now += kS;
  sup.OnHeartbeat(Heartbeat("vehicle_sim", 100, HeartbeatState::kWarn, now));
  EXPECT_EQ(Starts(sup.Tick(now)), (std::vector<size_t>{1}));
  sup.OnStarted(1, 101, now);
  // ladar wants OK: WARN is not enough.
  sup.OnHeartbeat(Heartbeat("ladar_driver", 101, HeartbeatState::kWarn, now + kS / 2));
  EXPECT_TRUE(Starts(sup.Tick(now + kS / 2)).empty());
  EXPECT_EQ(sup.Status(now + kS / 2)[1].state_text, "starting (ready = ok)");
  sup.OnHeartbeat(Heartbeat("ladar_driver", 101, HeartbeatState::kOk, now + kS));
  EXPECT_EQ(Starts(sup.Tick(now + kS)), (std::vector<size_t>{2}));
  sup.OnStarted(2, 102, now + kS);
  EXPECT_TRUE(Starts(sup.Tick(now + 2 * kS)).empty());
  for (const ProcessStatus& row : sup.Status(now + 2 * kS)) EXPECT_EQ(row.state, ProcessState::kRunning) << row.name;
  EXPECT_EQ(sup.Health(), HeartbeatState::kOk);
  EXPECT_EQ(sup.Summary(), "4 running");
}

TEST(Supervisor, RestartsWithBackoffThenGivesUpACrashLoopWithItsReason) {
  Supervisor sup(Fleet("[process crash]\ncommand = /bin/false\ngroup = g\n[process sleep]\ncommand = sleep 100\ngroup = g\n"),
                 FastRestarts());
  int64_t now = kT0;
  ASSERT_EQ(Starts(sup.Tick(now)), (std::vector<size_t>{0, 1}));
  sup.OnStarted(0, 10, now);
  sup.OnStarted(1, 11, now);
  sup.TakeEvents();
  std::vector<int64_t> restart_delays;
  int pid = 20;
  for (int failure = 1; failure <= 3; ++failure) {
    now += kS / 100;  // exits 10 ms after it starts
    sup.OnExited(0, ExitStatus{1, 0}, now);
    ASSERT_EQ(sup.Status(now)[0].state, ProcessState::kRestarting);
    EXPECT_EQ(sup.Health(), HeartbeatState::kWarn) << "restarting is trouble";
    // Not before its time: poll every 10 ms until the start comes.
    const int64_t exited = now;
    while (Starts(sup.Tick(now)).empty()) now += kS / 100;
    restart_delays.push_back(now - exited);
    sup.OnStarted(0, pid++, now);
  }
  EXPECT_EQ(restart_delays, (std::vector<int64_t>{kS / 2, kS, 2 * kS}));
  EXPECT_EQ(sup.Status(now)[0].restarts, 3);
  EXPECT_EQ(sup.Health(), HeartbeatState::kOk) << "running again";

  now += kS / 100;
  sup.OnExited(0, ExitStatus{1, 0}, now);
  const ProcessStatus row = sup.Status(now)[0];
  EXPECT_EQ(row.state, ProcessState::kGivenUp);
  EXPECT_EQ(row.state_text, "GIVEN UP: crash loop: 4 failures within 30 s (last: exit code 1)");
  EXPECT_TRUE(Starts(sup.Tick(now + 100 * kS)).empty()) << "given up means no more starts";
  const std::vector<std::string> events = sup.TakeEvents();
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.back(), "crash GIVEN UP: crash loop: 4 failures within 30 s (last: exit code 1); no more restarts");
  EXPECT_FALSE(sup.end()) << "not required: the rest of the fleet goes on";
  EXPECT_EQ(sup.Summary(), "1 running, 1 given up; crash given up");
}

TEST(Supervisor, ARestartingProcessShowsItsCountdown) {
  Supervisor sup(Fleet("[process a]\ncommand = x\ngroup = g\n"), FastRestarts());
  sup.Tick(kT0);
  sup.OnStarted(0, 5, kT0);
  sup.OnExited(0, ExitStatus{0, SIGSEGV}, kT0 + 20 * kS);  // ran 20 s: stable, first failure in a row
  EXPECT_EQ(sup.Status(kT0 + 20 * kS)[0].state_text, "restarting in 0.5 s");
  EXPECT_EQ(sup.Status(kT0 + 20 * kS + kS / 5)[0].state_text, "restarting in 0.3 s");
  EXPECT_EQ(sup.TakeEvents().back(), "a killed by SIGSEGV: restarting in 0.5 s (failure 1 in a row)");
}

TEST(Supervisor, ARequiredProcessGivenUpEndsTheFleet) {
  RestartOptions o = FastRestarts();
  o.crash_loop_failures = 1;
  Supervisor sup(Fleet("[process a]\ncommand = x\ngroup = g\nrequired = true\n[process b]\ncommand = y\ngroup = g\n"), o);
  sup.Tick(kT0);
  sup.OnStarted(0, 5, kT0);
  sup.OnStarted(1, 6, kT0);
  sup.OnExited(0, ExitStatus{3, 0}, kT0 + kS);
  ASSERT_TRUE(sup.end());
  EXPECT_EQ(sup.end()->exit_code, 3);
  EXPECT_EQ(sup.end()->reason, "required process a given up: crash loop: 1 failures within 30 s (last: exit code 3)");
  // The node then stops the rest: b is signalled, and its exit is a stop, not a failure.
  EXPECT_EQ(sup.BeginStop("required"), (std::vector<size_t>{1}));
  EXPECT_TRUE(sup.Tick(kT0 + 2 * kS).empty());
  sup.OnExited(1, ExitStatus{0, 0}, kT0 + 2 * kS);
  EXPECT_EQ(sup.Status(kT0 + 2 * kS)[1].state, ProcessState::kStopped);
  EXPECT_TRUE(sup.NoneRunning());
}

TEST(Supervisor, StoppingSignalsTheRunningOnesAndStartsNothingMore) {
  Supervisor sup(Fleet("[process a]\ncommand = /b/vehicle_sim\ngroup = g\nready = heartbeat\n"
                       "[process b]\ncommand = y\ngroup = g\nafter = a\n"
                       "[process c]\ncommand = z\ngroup = g\n"),
                 FastRestarts());
  EXPECT_EQ(Starts(sup.Tick(kT0)), (std::vector<size_t>{0, 2}));
  sup.OnStarted(0, 5, kT0);
  sup.OnStarted(2, 6, kT0);
  sup.OnExited(2, ExitStatus{1, 0}, kT0 + kS);  // c restarts in 0.5 s
  EXPECT_EQ(sup.BeginStop("stop signal"), (std::vector<size_t>{0}));
  EXPECT_TRUE(sup.stopping());
  EXPECT_FALSE(sup.NoneRunning());
  EXPECT_TRUE(sup.Tick(kT0 + 10 * kS).empty()) << "no restart of c, no start of b";
  sup.OnExited(0, ExitStatus{0, 0}, kT0 + 2 * kS);
  EXPECT_TRUE(sup.NoneRunning());
  const std::vector<ProcessStatus> rows = sup.Status(kT0 + 2 * kS);
  EXPECT_EQ(rows[0].state_text, "stopped (exit code 0)");
  EXPECT_EQ(rows[1].state_text, "stopped (never started)");
  EXPECT_EQ(rows[2].state_text, "stopped (not restarted)");
  EXPECT_FALSE(sup.end()) << "a stop from outside is no end of the fleet by itself";
}

TEST(Supervisor, AProcessThatEndsTheFleetGivesItsExitCode) {
  Supervisor sup(Fleet("[process client]\ncommand = x\ngroup = g\nends_fleet = true\n[process b]\ncommand = y\ngroup = g\n"),
                 FastRestarts());
  sup.Tick(kT0);
  sup.OnStarted(0, 5, kT0);
  sup.OnStarted(1, 6, kT0);
  sup.OnExited(0, ExitStatus{0, 0}, kT0 + 3 * kS);
  ASSERT_TRUE(sup.end());
  EXPECT_EQ(sup.end()->exit_code, 0);
  EXPECT_EQ(sup.end()->reason, "client ended (exit code 0), and it ends the fleet");
}

TEST(Supervisor, AOneShotStepThatEndedWellReleasesThoseAfterIt) {
  Supervisor sup(Fleet("[process world]\ncommand = gen\ngroup = g\nrestart = never\nready = exited\n"
                       "[process sim]\ncommand = sim\ngroup = g\nafter = world\n"),
                 FastRestarts());
  EXPECT_EQ(Starts(sup.Tick(kT0)), (std::vector<size_t>{0}));
  sup.OnStarted(0, 5, kT0);
  EXPECT_EQ(Starts(sup.Tick(kT0)), std::vector<size_t>{}) << "world runs, but sim waits for it to be done";
  EXPECT_EQ(sup.Status(kT0)[0].state_text, "starting (ready = exited)");
  sup.OnExited(0, ExitStatus{0, 0}, kT0 + kS);
  EXPECT_EQ(sup.Status(kT0 + kS)[0].state_text, "exited: exit code 0");
  EXPECT_EQ(Starts(sup.Tick(kT0 + kS)), (std::vector<size_t>{1}));
  EXPECT_EQ(sup.Health(), HeartbeatState::kOk);

  // The same step failing: sim can never start, and the fleet is over.
  Supervisor failing(Fleet("[process world]\ncommand = gen\ngroup = g\nrestart = never\nready = exited\n"
                           "[process sim]\ncommand = sim\ngroup = g\nafter = world\n"),
                     FastRestarts());
  failing.Tick(kT0);
  failing.OnStarted(0, 5, kT0);
  failing.OnExited(0, ExitStatus{2, 0}, kT0 + kS);
  EXPECT_TRUE(failing.Tick(kT0 + kS).empty());
  ASSERT_TRUE(failing.end());
  EXPECT_EQ(failing.end()->exit_code, 3);
  EXPECT_EQ(failing.Status(kT0 + kS)[1].state_text, "waiting for world");
}

TEST(Supervisor, NotReadyInTimeIsStoppedAndCountsAsAFailure) {
  Supervisor sup(Fleet("[process a]\ncommand = /b/vehicle_sim\ngroup = g\nready = ok\nready_timeout = 2\n"), FastRestarts());
  sup.Tick(kT0);
  sup.OnStarted(0, 5, kT0);
  EXPECT_TRUE(sup.Tick(kT0 + kS).empty());
  const std::vector<SupervisorAction> actions = sup.Tick(kT0 + 2 * kS);
  ASSERT_EQ(actions.size(), 1u);
  EXPECT_EQ(actions[0].kind, SupervisorAction::Kind::kStop);
  EXPECT_EQ(sup.Status(kT0 + 2 * kS)[0].state, ProcessState::kStopping);
  sup.OnExited(0, ExitStatus{0, 0}, kT0 + 2 * kS + kS / 10);  // it exited 0 on SIGINT: still a failure
  EXPECT_EQ(sup.Status(kT0 + 2 * kS + kS / 10)[0].state, ProcessState::kRestarting);
  const std::vector<std::string> events = sup.TakeEvents();
  EXPECT_EQ(events.back(),
            "a not ready after 2.0 s (ready = ok: no such HEARTBEAT from vehicle_sim), then exit code 0: restarting in "
            "0.5 s (failure 1 in a row)");
}

TEST(Supervisor, NothingLeftToSuperviseEndsTheFleet) {
  Supervisor sup(Fleet("[process a]\ncommand = x\ngroup = g\n[process b]\ncommand = y\ngroup = g\n"), FastRestarts());
  sup.Tick(kT0);
  sup.OnStarted(0, 5, kT0);
  sup.OnStarted(1, 6, kT0);
  sup.OnExited(0, ExitStatus{0, 0}, kT0 + kS);
  EXPECT_FALSE(sup.end());
  sup.OnExited(1, ExitStatus{0, 0}, kT0 + kS);
  ASSERT_TRUE(sup.end());
  EXPECT_EQ(sup.end()->exit_code, 0);
  EXPECT_EQ(sup.end()->reason, "nothing left to supervise: every process ended well");
}

TEST(Supervisor, AStartThatFailsIsAFailureLikeAnExit) {
  Supervisor sup(Fleet("[process a]\ncommand = x\ngroup = g\n"), FastRestarts());
  sup.Tick(kT0);
  sup.OnStartFailed(0, "cannot open /o/a.log", kT0);
  EXPECT_EQ(sup.Status(kT0)[0].state, ProcessState::kRestarting);
  EXPECT_EQ(sup.TakeEvents().back(), "a could not start: cannot open /o/a.log: restarting in 0.5 s (failure 1 in a row)");
}

TEST(StatusTable, ColumnsLineUpAndShowHeartbeatsAndRates) {
  Supervisor sup(Fleet(kChain), FastRestarts());
  int64_t now = kT0;
  sup.Tick(now);
  sup.OnStarted(0, 100, now);
  sup.OnStarted(3, 103, now);
  // Two heartbeats 1 s apart, 20 messages handled between them: 20 messages/s.
  HeartbeatSample first = Heartbeat("vehicle_sim", 100, HeartbeatState::kOk, now + kS, 5);
  HeartbeatSample second = Heartbeat("vehicle_sim", 100, HeartbeatState::kOk, now + 2 * kS, 25);
  second.message = "idle: no fresh command";
  sup.OnHeartbeat(first);
  sup.OnHeartbeat(second);
  ASSERT_EQ(Starts(sup.Tick(now + 2 * kS)), (std::vector<size_t>{1}));
  sup.OnStarted(1, 101, now + 2 * kS);
  now += 2 * kS + 400'000;
  const std::string table = FleetStatusTable(sup.Status(now), now);
  EXPECT_EQ(table,
            "process  group    state                  pid  restarts  heartbeat  hb state  msgs/s  message\n"
            "sim      vehicle  running                100  0         0.4 s      OK        20.0    idle: no fresh command\n"
            "ladar    vehicle  starting (ready = ok)  101  0         -          -         -\n"
            "mapper   vehicle  waiting for ladar      -    0         -          -         -\n"
            "logger   base     running                103  0         -          -         -\n");
}

}  // namespace
}  // namespace minenav
