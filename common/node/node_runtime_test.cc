#include "common/node/node_runtime.h"

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>

#include "common/file_io.h"
#include "common/node/event_log.h"
#include "common/node/fake_bus.h"
#include "common/node/fake_runtime.h"
#include "common/node/log_bus.h"
#include "minenav/drive_command_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/vehicle_truth_t.hpp"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

namespace fs = std::filesystem;

using testing::TempPath;

odometry_t Odometry(int64_t utime, double x) {
  odometry_t m{};
  m.utime = utime;
  m.pose.x = x;
  return m;
}

template <typename T>
std::vector<T> ReadChannel(const std::string& path, const std::string& channel,
                           std::vector<int64_t>* timestamps = nullptr) {
  std::vector<T> out;
  LogReader reader(path);
  while (auto e = reader.Next()) {
    if (e->channel != channel) continue;
    T m{};
    std::string error;
    if (!DecodeMessage(e->data.data(), static_cast<int>(e->data.size()), channel, &m, &error))
      throw std::runtime_error(error);
    out.push_back(m);
    if (timestamps) timestamps->push_back(e->timestamp);
  }
  return out;
}

constexpr int64_t kT0 = 1'700'000'000'000'000;  // us

// Nine odometry events 0.25 s apart, plus a wrong-type and a truncated message.
std::string WriteInputLog() {
  const std::string path = TempPath("input.lcm");
  LogWriter writer(path);
  for (int k = 0; k <= 8; ++k) {
    writer.Write("ODOMETRY", Odometry(kT0 + k * 250'000, k));
    if (k == 3) {
      drive_command_t wrong{};
      writer.WriteMessage("ODOMETRY", kT0 + k * 250'000 + 1, wrong);
      const std::vector<uint8_t> full = EncodeMessage(Odometry(0, 0));
      writer.Write("ODOMETRY", kT0 + k * 250'000 + 2, full.data(), 20);
    }
  }
  writer.Close();
  return path;
}

struct BatchRecord {
  std::vector<int64_t> timer_times;
  std::vector<int64_t> handled_before_timer;
  std::vector<int64_t> clock_in_handler;
};

// A small node: echoes ODOMETRY as SIM_TRUTH and runs a 10 Hz timer.
BatchRecord RunBatchNode(const std::string& input, const std::string& output, double run_for = 0) {
  NodeOptions options;
  options.log = input;
  options.log_out = output;
  options.heartbeat_period = 0.5;
  options.run_for = run_for;
  NodeRuntime runtime("test_node", options);
  runtime.Start();
  EXPECT_TRUE(runtime.batch());
  BatchRecord rec;
  int64_t handled = 0;
  Subscribe<odometry_t>(runtime.bus(), "ODOMETRY", [&](const odometry_t& m) {
    ++handled;
    rec.clock_in_handler.push_back(runtime.NowUtime());
    vehicle_truth_t t{};
    t.utime = m.utime;
    t.pose.x = m.pose.x;
    Publish(runtime.bus(), "SIM_TRUTH", t);
  });
  runtime.AddTimer(0.1, [&](int64_t utime) {
    EXPECT_EQ(utime, runtime.NowUtime());
    rec.timer_times.push_back(utime);
    rec.handled_before_timer.push_back(handled);
  });
  EXPECT_EQ(runtime.Run(), 0);
  return rec;
}

TEST(NodeRuntimeBatch, TimersFireAtMessageTimeInOrder) {
  const std::string input = WriteInputLog();
  const std::string output = TempPath("out.lcm");
  const BatchRecord rec = RunBatchNode(input, output);

  // 10 Hz over [t0, t0 + 2 s] (the last event is at 2.0 s + 0): 21 firings.
  ASSERT_EQ(rec.timer_times.size(), 21u);
  for (size_t i = 0; i < rec.timer_times.size(); ++i) {
    EXPECT_EQ(rec.timer_times[i], kT0 + static_cast<int64_t>(i) * 100'000);
    // A timer due at t fires before the event at t: events strictly earlier were handled.
    const int64_t expected = static_cast<int64_t>((static_cast<int64_t>(i) * 100'000 + 249'999) / 250'000);
    EXPECT_EQ(rec.handled_before_timer[i], expected) << "firing " << i;
  }
  // Handlers see the clock at their event's timestamp.
  ASSERT_EQ(rec.clock_in_handler.size(), 9u);
  for (int k = 0; k <= 8; ++k) EXPECT_EQ(rec.clock_in_handler[static_cast<size_t>(k)], kT0 + k * 250'000);

  // Outputs went to the output log, stamped with the batch clock.
  std::vector<int64_t> stamps;
  const auto truth = ReadChannel<vehicle_truth_t>(output, "SIM_TRUTH", &stamps);
  ASSERT_EQ(truth.size(), 9u);
  for (int k = 0; k <= 8; ++k) {
    EXPECT_EQ(truth[static_cast<size_t>(k)].utime, kT0 + k * 250'000);
    EXPECT_EQ(stamps[static_cast<size_t>(k)], kT0 + k * 250'000);
    EXPECT_DOUBLE_EQ(truth[static_cast<size_t>(k)].pose.x, k);
  }
  // Heartbeats every 0.5 s of log time, then STOPPING with the counts.
  const auto hb = ReadChannel<heartbeat_t>(output, "HEARTBEAT");
  ASSERT_EQ(hb.size(), 6u);
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(hb[i].utime, kT0 + static_cast<int64_t>(i) * 500'000);
    EXPECT_EQ(hb[i].state, heartbeat_t::OK);
    EXPECT_EQ(hb[i].process, "test_node");
    EXPECT_EQ(hb[i].seq, static_cast<int64_t>(i));
  }
  EXPECT_EQ(hb.back().state, heartbeat_t::STOPPING);
  EXPECT_EQ(hb.back().messages_in, 9);
  EXPECT_EQ(hb.back().messages_bad, 2);
  EXPECT_EQ(hb.back().pid, ::getpid());
}

TEST(NodeRuntimeBatch, RepeatedRunsWriteIdenticalLogs) {
  const std::string input = WriteInputLog();
  const std::string a = TempPath("a.lcm"), b = TempPath("b.lcm");
  RunBatchNode(input, a);
  RunBatchNode(input, b);
  std::ifstream fa(a, std::ios::binary), fb(b, std::ios::binary);
  const std::string da((std::istreambuf_iterator<char>(fa)), {});
  const std::string db((std::istreambuf_iterator<char>(fb)), {});
  EXPECT_FALSE(da.empty());
  EXPECT_EQ(da, db);
}

TEST(NodeRuntimeBatch, RunForStopsEarly) {
  const std::string input = WriteInputLog();
  const std::string output = TempPath("runfor.lcm");
  const BatchRecord rec = RunBatchNode(input, output, 0.6);
  EXPECT_EQ(rec.clock_in_handler.size(), 3u);  // events at 0, 0.25, 0.5 s
  EXPECT_EQ(rec.timer_times.size(), 6u);       // 0 .. 0.5 s
}

TEST(NodeRuntimeBatch, BadOptionsAndFiles) {
  NodeOptions options;
  options.log_out = TempPath("x.lcm");
  EXPECT_THROW(NodeRuntime("n", options).Start(), UsageError);
  options.log = TempPath("does_not_exist.lcm");
  EXPECT_THROW(NodeRuntime("n", options).Start(), InputError);
  options.log_out = options.log;
  EXPECT_THROW(NodeRuntime("n", options).Start(), UsageError);
  NodeOptions live;
  live.lcm_url = "239.255.76.67:7667";
  EXPECT_THROW(NodeRuntime("n", live).Start(), UsageError);
}

TEST(NodeRuntimeLive, HeartbeatsCountsAndTimersOnAFakeBus) {
  auto owned = std::make_unique<FakeBus>();
  FakeBus& bus = *owned;
  ManualClock clock(kT0);
  NodeOptions options;
  options.heartbeat_period = 1.0;
  NodeRuntime runtime("fake_node", options);
  runtime.StartWith(std::move(owned), clock);
  int handled = 0;
  Subscribe<odometry_t>(runtime.bus(), "ODOMETRY", [&](const odometry_t&) { ++handled; });
  std::vector<int64_t> ticks;
  runtime.AddTimer(0.25, [&](int64_t t) { ticks.push_back(t); });

  runtime.SpinOnce(0);  // t0: first heartbeat and first tick
  bus.InjectMessage("ODOMETRY", Odometry(1, 1));
  bus.Inject("ODOMETRY", {1, 2, 3});  // garbage
  clock.Advance(500'000);
  EXPECT_EQ(runtime.SpinOnce(0), 2);
  EXPECT_EQ(handled, 1);
  clock.Advance(600'000);  // t0 + 1.1 s
  runtime.SpinOnce(0);
  runtime.SetStatus(heartbeat_t::WARN, "no scans");
  clock.Advance(1'000'000);
  runtime.SpinOnce(0);
  runtime.Shutdown();

  const auto hb = bus.Decoded<heartbeat_t>("HEARTBEAT");
  ASSERT_EQ(hb.size(), 4u);
  EXPECT_EQ(hb[0].state, heartbeat_t::OK);
  EXPECT_EQ(hb[0].messages_in, 0);
  EXPECT_EQ(hb[1].messages_in, 1);
  EXPECT_EQ(hb[1].messages_bad, 1);
  EXPECT_EQ(hb[2].state, heartbeat_t::WARN);
  EXPECT_EQ(hb[2].message, "no scans");
  EXPECT_EQ(hb[3].state, heartbeat_t::STOPPING);
  // Live timers fire at the current time and skip missed periods.
  EXPECT_EQ(ticks, (std::vector<int64_t>{kT0, kT0 + 500'000, kT0 + 1'100'000, kT0 + 2'100'000}));
}

TEST(NodeRuntimeLive, SigtermStopsRunWithAStoppingHeartbeat) {
  auto owned = std::make_unique<FakeBus>();
  FakeBus& bus = *owned;
  ManualClock clock(kT0);
  NodeRuntime runtime("sig_node", NodeOptions{});
  runtime.StartWith(std::move(owned), clock);
  bool hook_ran = false;
  runtime.OnShutdown([&] { hook_ran = true; });
  int ticks = 0;
  runtime.AddTimer(0.1, [&](int64_t) {
    clock.Advance(100'000);
    if (++ticks == 5) std::raise(SIGTERM);
  });
  NodeRuntime::InstallSignalHandlers();
  EXPECT_EQ(runtime.Run(), 0);
  NodeRuntime::ClearStopSignal();
  EXPECT_EQ(ticks, 5);
  EXPECT_TRUE(hook_ran);
  const auto hb = bus.Decoded<heartbeat_t>("HEARTBEAT");
  ASSERT_FALSE(hb.empty());
  EXPECT_EQ(hb.back().state, heartbeat_t::STOPPING);
}

// systemd's notify protocol. The test owns a datagram socket where systemd would be, and
// points $NOTIFY_SOCKET (and $WATCHDOG_USEC, as systemd sets it for WatchdogSec=) at it.
class NotifySocket {
 public:
  NotifySocket() : path_(TempPath("notify_" + std::to_string(next_++) + ".sock")) {
    fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    path_.copy(address.sun_path, sizeof(address.sun_path) - 1);
    ::unlink(path_.c_str());
    if (fd_ < 0 || ::bind(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0)
      throw std::runtime_error("cannot bind " + path_);
  }
  ~NotifySocket() {
    ::close(fd_);
    ::unlink(path_.c_str());
  }
  const std::string& path() const { return path_; }
  // Every datagram received since the last call.
  std::vector<std::string> Take() {
    std::vector<std::string> got;
    char buffer[4096];
    for (ssize_t n; (n = ::recv(fd_, buffer, sizeof(buffer), 0)) >= 0;) got.emplace_back(buffer, static_cast<size_t>(n));
    return got;
  }

 private:
  static inline int next_ = 0;
  std::string path_;
  int fd_ = -1;
};

// Environment variables set for one test, then put back as they were.
class ScopedEnv {
 public:
  ScopedEnv(const std::string& name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name.c_str())) old_ = old;
    if (value != nullptr) {
      ::setenv(name.c_str(), value, 1);
    } else {
      ::unsetenv(name.c_str());
    }
  }
  ~ScopedEnv() {
    if (old_) {
      ::setenv(name_.c_str(), old_->c_str(), 1);
    } else {
      ::unsetenv(name_.c_str());
    }
  }

 private:
  std::string name_;
  std::optional<std::string> old_;
};

TEST(NodeRuntimeSystemd, ReadyThenWatchdogAtHalfThePeriodFromTheLoopThenStopping) {
  NotifySocket systemd;
  ScopedEnv socket("NOTIFY_SOCKET", systemd.path().c_str());
  ScopedEnv watchdog("WATCHDOG_USEC", "200000");  // WatchdogSec=0.2
  ScopedEnv watchdog_pid("WATCHDOG_PID", nullptr);
  ManualClock clock(kT0);
  FakeRuntime fake(clock, /*heartbeat_period=*/1.0);
  EXPECT_EQ(fake.runtime().watchdog_usec(), 200'000);
  fake.runtime().SetStatus(heartbeat_t::OK, "driving");
  EXPECT_TRUE(systemd.Take().empty()) << "nothing before the loop runs";

  fake.runtime().SpinOnce(0);  // the loop starts: READY, the first heartbeat's STATUS, a ping
  EXPECT_EQ(systemd.Take(), (std::vector<std::string>{"READY=1\nSTATUS=running", "STATUS=OK: driving", "WATCHDOG=1"}));

  // 1 s of a loop turning every 10 ms: a ping every 0.1 s (half of WatchdogSec), no more.
  int pings = 0;
  for (int step = 1; step <= 100; ++step) {
    clock.Advance(10'000);
    fake.runtime().SpinOnce(0);
    for (const std::string& m : systemd.Take()) {
      if (m == "WATCHDOG=1") ++pings;
      else EXPECT_EQ(m, "STATUS=OK: driving") << "the status is sent again only when it changes";
    }
  }
  EXPECT_EQ(pings, 10);

  // A loop that stops turning sends nothing: 1 s without a spin, then one ping (missed
  // periods are skipped, not made up in a burst).
  clock.Advance(1'000'000);
  EXPECT_TRUE(systemd.Take().empty());
  fake.runtime().SpinOnce(0);
  const std::vector<std::string> after_stall = systemd.Take();
  EXPECT_EQ(std::count(after_stall.begin(), after_stall.end(), "WATCHDOG=1"), 1);

  fake.runtime().SetStatus(heartbeat_t::WARN, "no odometry");
  clock.Advance(1'000'000);
  fake.runtime().SpinOnce(0);
  const std::vector<std::string> warned = systemd.Take();
  EXPECT_NE(std::find(warned.begin(), warned.end(), "STATUS=WARN: no odometry"), warned.end());

  fake.runtime().Shutdown();
  const std::vector<std::string> stopping = systemd.Take();
  ASSERT_FALSE(stopping.empty());
  EXPECT_EQ(stopping.front(), "STOPPING=1");
  EXPECT_EQ(stopping.back(), "STATUS=STOPPING: no odometry");
}

TEST(NodeRuntimeSystemd, WithoutNotifySocketOrForAnotherPidNothingIsSent) {
  NotifySocket systemd;
  {
    ScopedEnv socket("NOTIFY_SOCKET", nullptr);  // not under systemd
    ScopedEnv watchdog("WATCHDOG_USEC", "200000");
    ManualClock clock(kT0);
    FakeRuntime fake(clock, 1.0);
    for (int step = 0; step < 50; ++step) {
      fake.runtime().SpinOnce(0);
      clock.Advance(20'000);
    }
    fake.runtime().Shutdown();
    EXPECT_TRUE(systemd.Take().empty());
  }
  {
    // $WATCHDOG_USEC meant for another process (a child inherited it): no watchdog timer.
    ScopedEnv socket("NOTIFY_SOCKET", systemd.path().c_str());
    ScopedEnv watchdog("WATCHDOG_USEC", "200000");
    ScopedEnv watchdog_pid("WATCHDOG_PID", std::to_string(::getpid() + 1).c_str());
    ManualClock clock(kT0);
    FakeRuntime fake(clock, 0.0);
    EXPECT_EQ(fake.runtime().watchdog_usec(), 0);
    for (int step = 0; step < 50; ++step) {
      fake.runtime().SpinOnce(0);
      clock.Advance(20'000);
    }
    EXPECT_EQ(systemd.Take(), (std::vector<std::string>{"READY=1\nSTATUS=running"}));
  }
}

TEST(NodeRuntimeOptions, RegisteredInTheSchema) {
  ConfigSchema schema("opt_node", "test");
  NodeRuntime runtime("opt_node", schema);
  schema.Parse({"--lcm-url", "udpm://239.255.76.67:7702?ttl=0", "--heartbeat-period=0.25",
                "--log-level=warn", "--instance", "left"});
  EXPECT_EQ(runtime.options().lcm_url, "udpm://239.255.76.67:7702?ttl=0");
  EXPECT_DOUBLE_EQ(runtime.options().heartbeat_period, 0.25);
  EXPECT_EQ(runtime.options().instance, "left");
  EXPECT_THROW(schema.Parse({"--log-level=verbose"}), UsageError);
  EXPECT_THROW(schema.Parse({"--heartbeat-period=-1"}), UsageError);
  const std::string help = schema.HelpText();
  for (const char* flag : {"--lcm-url", "--log", "--log-out", "--heartbeat-period", "--run-for", "HEARTBEAT"})
    EXPECT_NE(help.find(flag), std::string::npos) << flag;
}

// Issue 11, item 12: a batch run stopped by SIGTERM part-way exited 0 and renamed its
// --log-out from .partial as if it were complete.
TEST(NodeRuntimeBatch, SignalBeforeTheEndOfTheLogKeepsOutputsAsPartial) {
  const std::string input = WriteInputLog();
  const std::string output = TempPath("interrupted.lcm");
  NodeOptions options;
  options.log = input;
  options.log_out = output;
  options.heartbeat_period = 0;
  NodeRuntime runtime("test_node", options);
  runtime.Start();
  int handled = 0;
  bool hook_saw_interruption = false;
  Subscribe<odometry_t>(runtime.bus(), "ODOMETRY", [&](const odometry_t& m) {
    vehicle_truth_t t{};
    t.utime = m.utime;
    Publish(runtime.bus(), "SIM_TRUTH", t);
    if (++handled == 4) std::raise(SIGTERM);
  });
  runtime.OnShutdown([&] { hook_saw_interruption = runtime.interrupted(); });
  EXPECT_EQ(runtime.Run(), kExitInterrupted);
  NodeRuntime::ClearStopSignal();
  EXPECT_EQ(handled, 4);
  EXPECT_TRUE(runtime.interrupted());
  EXPECT_TRUE(hook_saw_interruption);
  EXPECT_FALSE(fs::exists(output)) << "an interrupted run must not leave a file claiming to be complete";
  ASSERT_TRUE(fs::exists(output + ".partial"));
  EXPECT_EQ(ReadChannel<vehicle_truth_t>(output + ".partial", "SIM_TRUTH").size(), 4u);
}

// Issue 11, item 5: stamps far in the future (INT64_MAX) or negative are rejected before
// any handler sees them, and HEARTBEAT says so.
TEST(NodeRuntimeLive, StampsOutsideTheWindowAreRejectedAndReported) {
  auto owned = std::make_unique<FakeBus>();
  FakeBus& bus = *owned;
  bus.set_max_stamp_lead_us(10'000'000);
  ManualClock clock(kT0);
  NodeOptions options;
  options.heartbeat_period = 1.0;
  NodeRuntime runtime("stamp_node", options);
  runtime.StartWith(std::move(owned), clock);
  std::vector<int64_t> seen;
  Subscribe<odometry_t>(runtime.bus(), "ODOMETRY", [&](const odometry_t& m) { seen.push_back(m.utime); });
  runtime.SpinOnce(0);  // first heartbeat: OK
  bus.InjectMessage("ODOMETRY", Odometry(kT0, 1), kT0);
  bus.InjectMessage("ODOMETRY", Odometry(INT64_MAX, 2), kT0);
  bus.InjectMessage("ODOMETRY", Odometry(INT64_MIN, 3), kT0);
  bus.InjectMessage("ODOMETRY", Odometry(kT0 + 9'000'000, 4), kT0);  // inside the window
  bus.InjectMessage("ODOMETRY", Odometry(kT0 - 3'600'000'000, 5), kT0);  // an old log replayed: fine
  runtime.SpinOnce(0);
  clock.Advance(1'000'000);
  runtime.SpinOnce(0);  // heartbeat: WARN, says why
  clock.Advance(1'000'000);
  runtime.SpinOnce(0);  // nothing new: OK again
  EXPECT_EQ(seen, (std::vector<int64_t>{kT0, kT0 + 9'000'000, kT0 - 3'600'000'000}));
  EXPECT_EQ(runtime.bus().counters().stamps_rejected, 2);
  EXPECT_EQ(runtime.bus().counters().messages_bad, 2);
  const auto hb = bus.Decoded<heartbeat_t>("HEARTBEAT");
  ASSERT_EQ(hb.size(), 3u);
  EXPECT_EQ(hb[0].state, heartbeat_t::OK);
  EXPECT_EQ(hb[1].state, heartbeat_t::WARN);
  EXPECT_NE(hb[1].message.find("2 message(s) rejected for their timestamps"), std::string::npos) << hb[1].message;
  EXPECT_NE(hb[1].message.find("negative time"), std::string::npos) << hb[1].message;
  EXPECT_EQ(hb[2].state, heartbeat_t::OK);
}

// Issue 11, item 13: --heartbeat-period 1e-9 was accepted (49,023 HEARTBEATs in 2 s) and
// --scan-channel '((' crashed inside LCM.
TEST(NodeRuntimeOptions, AbsurdPeriodsAndChannelPatternsAreRefused) {
  NodeOptions options;
  options.heartbeat_period = 1e-9;
  options.log = WriteInputLog();
  NodeRuntime runtime("opt_node", options);
  EXPECT_THROW(runtime.Start(), UsageError);
  ConfigSchema schema("opt_node", "test");
  std::string channel = "LADAR_SCAN";
  schema.AddChannel("scan_channel", &channel, "subscribes", "ladar_scan_t", "scans");
  EXPECT_THROW(schema.Parse({"--scan-channel", "(("}), UsageError);
  EXPECT_THROW(schema.Parse({"--scan-channel", std::string(64, 'A')}), UsageError);
  EXPECT_NO_THROW(schema.Parse({"--scan-channel", "LADAR_SCAN_.*"}));
  EXPECT_EQ(channel, "LADAR_SCAN_.*");
  FakeBus bus;
  EXPECT_THROW(ValidateChannelPattern("a[b"), UsageError);
  EXPECT_NO_THROW(ValidateChannelPattern("POSE|POSE_IPE"));
}

TEST(RunNodeMain, ExitCodes) {
  EXPECT_EQ(RunNodeMain("t", [] { return 0; }), 0);
  EXPECT_EQ(RunNodeMain("t", []() -> int { throw UsageError("bad flag"); }), kExitUsage);
  EXPECT_EQ(RunNodeMain("t", []() -> int { throw InputError("bad file"); }), kExitUsage);
  EXPECT_EQ(RunNodeMain("t", []() -> int { throw std::runtime_error("boom"); }), kExitRuntime);
}

}  // namespace
}  // namespace minenav
