#include "fleet/supervisor_node.h"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <fstream>

#include "common/log.h"
#include "common/node/bus.h"
#include "fleet/child_launcher.h"
#include "common/node/heartbeat_conversion.h"
#include "fleet/status_table.h"
#include "minenav/heartbeat_t.hpp"

namespace minenav {

namespace {

// How often children are reaped and the supervision ticks.
constexpr double kPollPeriod = 0.05;  // s

std::atomic<int> g_status_requested{0};
extern "C" void OnStatusSignal(int) { g_status_requested.store(1); }

int64_t SecondsToUs(double s) { return static_cast<int64_t>(s * 1e6); }

std::string ClockText(int64_t utime) {
  const std::time_t t = static_cast<std::time_t>(utime / 1'000'000);
  std::tm tm{};
  ::localtime_r(&t, &tm);
  char text[16];
  std::strftime(text, sizeof(text), "%H:%M:%S", &tm);
  return text;
}

}  // namespace

void DeclareOptions(ConfigSchema& schema, SupervisorOptions& options) {
  schema.AddString("groups", &options.groups, "host groups to run, comma-separated (vehicle,base); empty = all");
  schema.AddString("out", &options.out,
                   "output folder: ${OUT} in the fleet file and each process's log NAME.log; "
                   "empty = out/fleet-<UTC time>");
  schema.AddDouble("status_period", &options.status_period, "s",
                   "time between status tables on stdout; 0 = only on SIGUSR1 and at the end", 0.0, 86400.0);
  schema.AddDouble("stop_grace", &options.stop_grace, "s",
                   "time a process has to exit after SIGINT before SIGKILL", 0.0, 600.0);
  DeclareOptions(OptionScope(schema).Nested("restart"), options.restart);
}

SupervisorNode::SupervisorNode(NodeRuntime& runtime, FleetSpec fleet, const SupervisorOptions& options)
    : runtime_(runtime), options_(options), supervisor_(std::move(fleet), options.restart) {
  Subscribe<heartbeat_t>(runtime_.bus(), runtime_.options().heartbeat_channel, [this](const heartbeat_t& m) {
    supervisor_.OnHeartbeat(HeartbeatSampleFromLcm(m, runtime_.NowUtime()));
  });
  runtime_.AddTimer(kPollPeriod, [this](int64_t now) { Poll(now); });
  if (options_.status_period > 0)
    runtime_.AddTimer(options_.status_period, [this, first = true](int64_t now) mutable {
      if (!first) PrintStatus(now);  // not when the timer first fires, at the start: nothing to see yet
      first = false;
    });
  runtime_.OnShutdown([this] {
    StopFleet(NodeRuntime::StopSignalled() ? "stop signal" : "the supervisor's run ended (--run-for)");
  });
  struct sigaction action {};
  action.sa_handler = &OnStatusSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGUSR1, &action, nullptr);
}

int SupervisorNode::Run() {
  MINENAV_LOG(kInfo) << "supervising " << supervisor_.fleet().processes.size() << " processes of "
                     << supervisor_.fleet().source << ", logs in " << options_.out;
  runtime_.Run();
  PrintStatus(runtime_.NowUtime());
  if (supervisor_.end()) {
    if (supervisor_.end()->exit_code == 0) {
      MINENAV_LOG(kInfo) << "fleet ended: " << supervisor_.end()->reason;
    } else {
      MINENAV_LOG(kError) << "fleet ended: " << supervisor_.end()->reason;
    }
    return supervisor_.end()->exit_code;
  }
  return 0;
}

void SupervisorNode::Poll(int64_t now) {
  ReapExits(now);
  for (const SupervisorAction& a : supervisor_.Tick(now)) {
    if (a.kind == SupervisorAction::Kind::kStart) {
      Start(a.process, now);
    } else {
      RequestStop(a.process, now);
    }
  }
  for (auto it = kill_at_.begin(); it != kill_at_.end();) {
    if (now >= it->second && running_.count(it->first) > 0) {
      MINENAV_LOG(kWarn) << supervisor_.fleet().processes[it->first].name << " did not exit within "
                         << options_.stop_grace << " s of SIGINT: SIGKILL";
      SignalProcessGroup(running_[it->first], SIGKILL);
      it = kill_at_.erase(it);
    } else {
      ++it;
    }
  }
  PrintEvents();
  runtime_.SetStatus(static_cast<int8_t>(supervisor_.Health()), supervisor_.Summary());
  if (g_status_requested.exchange(0) != 0) PrintStatus(now);
  if (supervisor_.end()) runtime_.RequestStop();
}

void SupervisorNode::Start(size_t i, int64_t now) {
  const ProcessSpec& spec = supervisor_.fleet().processes[i];
  LaunchRequest request;
  request.argv = spec.argv;
  request.env = spec.env;
  request.log_path = options_.out + "/" + spec.name + ".log";
  request.stdout_to_log = spec.stdout_to_log;
  {
    std::ofstream log(request.log_path, std::ios::app);
    log << "== fleet: " << (spec.argv.empty() ? "" : QuoteCommand(spec.argv)) << " (at " << ClockText(now) << ")\n";
  }
  try {
    const pid_t pid = LaunchProcess(request);
    running_[i] = pid;
    supervisor_.OnStarted(i, pid, now);
  } catch (const std::exception& e) {
    supervisor_.OnStartFailed(i, e.what(), now);
  }
}

void SupervisorNode::RequestStop(size_t i, int64_t now) {
  const auto it = running_.find(i);
  if (it == running_.end()) return;
  SignalProcessGroup(it->second, SIGINT);
  kill_at_[i] = now + SecondsToUs(options_.stop_grace);
}

void SupervisorNode::ReapExits(int64_t now) {
  for (auto it = running_.begin(); it != running_.end();) {
    if (const std::optional<ExitStatus> status = PollExit(it->second)) {
      // The process group may hold what a wrapper started: it goes with its leader.
      SignalProcessGroup(it->second, SIGKILL);
      const size_t i = it->first;
      it = running_.erase(it);
      kill_at_.erase(i);
      supervisor_.OnExited(i, *status, now);
    } else {
      ++it;
    }
  }
}

void SupervisorNode::StopFleet(const std::string& reason) {
  const std::string why = supervisor_.end() ? supervisor_.end()->reason : reason;
  for (const size_t i : supervisor_.BeginStop(why)) {
    const auto it = running_.find(i);
    if (it != running_.end()) SignalProcessGroup(it->second, SIGINT);
  }
  PrintEvents();
  // Wait for them all, SIGKILL the ones still there after the grace period. Polled here,
  // outside the node loop (it has ended).
  using SteadyClock = std::chrono::steady_clock;
  const auto kill_time = SteadyClock::now() + std::chrono::duration<double>(options_.stop_grace);
  bool killed = false;
  while (!running_.empty()) {
    ReapExits(runtime_.NowUtime());
    PrintEvents();
    if (running_.empty()) break;
    if (!killed && SteadyClock::now() >= kill_time) {
      for (const auto& [i, pid] : running_) {
        MINENAV_LOG(kWarn) << supervisor_.fleet().processes[i].name << " still running " << options_.stop_grace
                           << " s after SIGINT: SIGKILL";
        SignalProcessGroup(pid, SIGKILL);
      }
      killed = true;
    }
    // Waits on the bus: the processes' STOPPING heartbeats land in the final table.
    runtime_.bus().HandleFor(10'000);
  }
  runtime_.SetStatus(static_cast<int8_t>(supervisor_.Health()), supervisor_.Summary());
}

void SupervisorNode::PrintEvents() {
  for (const std::string& line : supervisor_.TakeEvents()) MINENAV_LOG(kInfo) << line;
}

void SupervisorNode::PrintStatus(int64_t now) const {
  std::string text = "== fleet status at " + ClockText(now) + " (" + supervisor_.fleet().source + ")\n";
  text += FleetStatusTable(supervisor_.Status(now), now);
  std::fputs(text.c_str(), stdout);
  std::fflush(stdout);
}

}  // namespace minenav
