#include "common/node/node_runtime.h"

#include <systemd/sd-daemon.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/file_io.h"
#include "common/log.h"
#include "common/node/lcm_bus.h"
#include "common/node/log_bus.h"
#include "minenav/heartbeat_t.hpp"

namespace minenav {

namespace {

std::atomic<int> g_stop_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler writes it");

// The first SIGINT/SIGTERM asks every loop to stop (outputs are written, the checkpoint
// saved); a second one, for a user who cannot wait, ends the process at once.
extern "C" void OnStopSignal(int /*signal*/) {
  if (g_stop_signal.exchange(1) != 0) {
    static const char kMessage[] = "second stop signal: exiting now, without writing outputs\n";
    const ssize_t ignored = ::write(2, kMessage, sizeof(kMessage) - 1);
    (void)ignored;
    ::_exit(kExitInterrupted);
  }
}

// Longest a live loop waits before looking at the stop flag again.
constexpr int64_t kMaxWaitUs = 100'000;
// In batch, a gap in the log longer than this many periods skips ahead instead of
// firing every missed period (a log spanning a day must not call a 10 Hz timer a
// million times between two events).
constexpr int64_t kMaxCatchUpPeriods = 100'000;

int64_t SecondsToUs(double s) { return static_cast<int64_t>(std::llround(s * 1e6)); }

}  // namespace

NodeRuntime::NodeRuntime(std::string process, ConfigSchema& schema)
    : process_(std::move(process)), state_(heartbeat_t::OK) {
  Register(schema);
}

NodeRuntime::NodeRuntime(std::string process, NodeOptions options)
    : process_(std::move(process)), options_(std::move(options)), state_(heartbeat_t::OK) {}

NodeRuntime::~NodeRuntime() = default;

void NodeRuntime::Register(ConfigSchema& schema) {
  schema.AddString("lcm_url", &options_.lcm_url,
                   "LCM URL; empty = $LCM_DEFAULT_URL, else " + std::string(kDefaultLcmUrl));
  schema.AddString("log", &options_.log,
                   "batch mode: read this LCM log instead of the bus, as fast as possible");
  schema.AddString("log_out", &options_.log_out, "batch mode: write publications to this LCM log");
  schema.AddDouble("heartbeat_period", &options_.heartbeat_period, "s",
                   "time between HEARTBEAT messages (0, or at least 0.01); 0 = none", 0.0, 3600.0);
  schema.AddString("log_level", &options_.log_level, "least severe message printed on stderr",
                   {"debug", "info", "warn", "error"});
  schema.AddInt("queue_capacity", &options_.queue_capacity,
                "messages each subscription buffers before LCM drops (live)", 1, 1'000'000);
  schema.AddDouble("run_for", &options_.run_for, "s",
                   "stop after this much clock time; 0 = until SIGINT/SIGTERM or end of log", 0.0,
                   1e9);
  schema.AddString("instance", &options_.instance, "instance name in HEARTBEAT (several copies)");
  schema.AddDouble("max_stamp_lead", &options_.max_stamp_lead, "s",
                   "reject messages stamped more than this after they were received, or before 0 "
                   "(clock skew allowance); 0 = no check",
                   0.0, 86400.0);
  schema.AddChannel("heartbeat_channel", &options_.heartbeat_channel, "publishes", "heartbeat_t",
                    "liveness, message counts and state");
  DeclareOptions(OptionScope(schema).Nested("auth"), options_.auth);
}

void NodeRuntime::WrapAuthentication() {
  if (options_.auth.key_file.empty()) return;
  if (!(options_.auth.max_age > 0) || !std::isfinite(options_.auth.max_age))
    throw UsageError("--auth.max-age must be > 0 s");
  const int64_t lead = bus_->max_stamp_lead_us();
  bus_ = std::make_unique<AuthBus>(std::move(bus_), options_.auth, *clock_);
  bus_->set_max_stamp_lead_us(lead);
}

void NodeRuntime::ApplyLogSettings() {
  SetLogProgramName(options_.instance.empty() ? process_ : process_ + ":" + options_.instance);
  try {
    SetLogLevel(ParseLogLevel(options_.log_level));
  } catch (const InputError& e) {
    throw UsageError(std::string("--log-level: ") + e.what());
  }
}

void NodeRuntime::Start() {
  if (bus_ != nullptr) throw std::logic_error("NodeRuntime::Start called twice");
  ApplyLogSettings();
  if (!options_.log_out.empty() && options_.log.empty())
    throw UsageError("--log-out is for batch mode: it needs --log");
  if (!options_.log.empty() && !options_.log_out.empty() && options_.log == options_.log_out)
    throw UsageError("--log-out must differ from --log");
  if (options_.heartbeat_period < 0 || !std::isfinite(options_.heartbeat_period) ||
      (options_.heartbeat_period > 0 && options_.heartbeat_period < kMinHeartbeatPeriod))
    throw UsageError("--heartbeat-period must be 0 (none) or at least " + std::to_string(kMinHeartbeatPeriod).substr(0, 4) +
                     " s, got " + std::to_string(options_.heartbeat_period));
  if (options_.max_stamp_lead < 0 || !std::isfinite(options_.max_stamp_lead))
    throw UsageError("--max-stamp-lead must be >= 0");
  if (!options_.log.empty()) {
    auto log_bus = std::make_unique<LogBus>(options_.log, batch_clock_);
    if (!options_.log_out.empty()) log_bus->SetOutputLog(options_.log_out);
    log_bus_ = log_bus.get();
    clock_ = &batch_clock_;
    bus_ = std::move(log_bus);
    bus_->set_max_stamp_lead_us(SecondsToUs(options_.max_stamp_lead));
    MINENAV_LOG(kInfo) << "batch over " << options_.log
                       << (options_.log_out.empty() ? "" : ", writing " + options_.log_out);
  } else {
    const std::string url = ResolveLcmUrl(options_.lcm_url);
    if (url.find("://") == std::string::npos)
      throw UsageError("LCM URL '" + url + "' is not a URL (e.g. " + kDefaultLcmUrl + ")");
    bus_ = std::make_unique<LcmBus>(url, options_.queue_capacity);
    bus_->set_max_stamp_lead_us(SecondsToUs(options_.max_stamp_lead));
    MINENAV_LOG(kDebug) << "LCM on " << url;
  }
  WrapAuthentication();
  if (options_.heartbeat_period > 0) {
    AddTimer(options_.heartbeat_period, [this](int64_t) { PublishHeartbeat(state_); });
  }
  if (!batch()) StartServiceWatchdog();
}

void NodeRuntime::StartWith(std::unique_ptr<Bus> bus, Clock& clock) {
  if (bus_ != nullptr) throw std::logic_error("NodeRuntime::StartWith called twice");
  ApplyLogSettings();
  bus_ = std::move(bus);
  clock_ = &clock;
  WrapAuthentication();
  if (options_.heartbeat_period > 0) {
    AddTimer(options_.heartbeat_period, [this](int64_t) { PublishHeartbeat(state_); });
  }
  StartServiceWatchdog();
}

void NodeRuntime::StartServiceWatchdog() {
  uint64_t usec = 0;
  // > 0 only when systemd set $WATCHDOG_USEC for this very process (WatchdogSec= in its unit).
  if (sd_watchdog_enabled(/*unset_environment=*/0, &usec) <= 0 || usec == 0) return;
  watchdog_usec_ = static_cast<int64_t>(usec);
  // A timer of the loop: it fires only while the loop turns, so a handler that hangs stops
  // the pings and systemd kills and restarts the process.
  AddTimer(static_cast<double>(usec) * 0.5e-6, [this](int64_t) { NotifyService("WATCHDOG=1"); });
}

void NodeRuntime::NotifyService(const std::string& state) const {
  if (batch()) return;
  // Returns 0 without $NOTIFY_SOCKET (not under systemd), < 0 on a send error: neither may
  // disturb the node, and a missed READY shows in systemd's own status.
  const int r = sd_notify(/*unset_environment=*/0, state.c_str());
  if (r < 0) MINENAV_LOG(kDebug) << "sd_notify failed: " << -r;
}

Bus& NodeRuntime::bus() {
  if (bus_ == nullptr) throw std::logic_error("NodeRuntime::bus() before Start()");
  return *bus_;
}

int NodeRuntime::AddTimer(double period_s, TimerCallback callback) {
  if (!(period_s > 0) || !std::isfinite(period_s))
    throw UsageError("timer period must be > 0 s, got " + std::to_string(period_s));
  Timer t;
  t.period_us = std::max<int64_t>(1, SecondsToUs(period_s));
  t.callback = std::move(callback);
  if (started_) {
    t.next_due = clock_->NowUtime();
    t.scheduled = true;
  }
  timers_.push_back(std::move(t));
  return static_cast<int>(timers_.size()) - 1;
}

void NodeRuntime::SetStatus(int8_t state, std::string message) {
  state_ = state;
  status_message_ = std::move(message);
}

void NodeRuntime::OnShutdown(std::function<void()> hook) { shutdown_hooks_.push_back(std::move(hook)); }

bool NodeRuntime::StopRequested() const { return stop_requested_ || g_stop_signal.load() != 0; }

bool NodeRuntime::StopSignalled() { return g_stop_signal.load() != 0; }

void NodeRuntime::InstallSignalHandlers() {
  struct sigaction action {};
  action.sa_handler = &OnStopSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;  // no SA_RESTART: a blocking wait returns so the loop can stop
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

void NodeRuntime::ClearStopSignal() { g_stop_signal.store(0); }

void NodeRuntime::PublishHeartbeat(int8_t state) {
  if (bus_ == nullptr) return;
  heartbeat_t hb{};
  hb.utime = clock_->NowUtime();
  hb.seq = heartbeat_seq_++;
  hb.process = process_;
  hb.instance = options_.instance;
  hb.pid = static_cast<int32_t>(::getpid());
  hb.state = state;
  hb.message = status_message_;
  hb.messages_in = bus_->counters().messages_in;
  hb.messages_bad = bus_->counters().messages_bad;
  // Messages rejected for their timestamps, or refused by authentication, since the last
  // heartbeat turn an OK into a WARN that says how many and why: a stream stamped outside the
  // window is a clock or sender fault, commands without the key someone on the network, and a
  // supervisor must see both (other bad messages show in messages_bad).
  auto warn_about = [&](int64_t total, int64_t* total_at_last, const char* what, const std::string& last) {
    const int64_t fresh = total - *total_at_last;
    *total_at_last = total;
    if (fresh <= 0 || state == heartbeat_t::STOPPING) return;
    if (hb.state == heartbeat_t::OK) hb.state = heartbeat_t::WARN;
    hb.message += std::string(hb.message.empty() ? "" : "; ") + std::to_string(fresh) + " message(s) " + what +
                  " since the last heartbeat (last: " + last + ")";
  };
  warn_about(bus_->counters().stamps_rejected, &stamps_rejected_at_last_heartbeat_, "rejected for their timestamps",
             bus_->last_stamp_rejection());
  warn_about(bus_->counters().auth_rejected, &auth_rejected_at_last_heartbeat_, "refused by authentication",
             bus_->last_auth_rejection());
  Publish(*bus_, options_.heartbeat_channel, hb);
  // systemctl status shows what the heartbeat says (sent when it changes).
  static const char* const kStateNames[] = {"STARTING", "OK", "WARN", "ERROR", "STOPPING"};
  std::string status = "STATUS=";
  status += hb.state >= 0 && hb.state <= 4 ? kStateNames[hb.state] : "?";
  if (!hb.message.empty()) status += ": " + hb.message;
  if (status != last_service_status_) {
    last_service_status_ = status;
    NotifyService(status);
  }
}

void NodeRuntime::BeginClock(int64_t utime) {
  if (started_) return;
  started_ = true;
  start_utime_ = utime;
  for (Timer& t : timers_) {
    if (!t.scheduled) {
      t.next_due = utime;
      t.scheduled = true;
    }
  }
  // The loop runs from here: a Type=notify unit is started.
  NotifyService("READY=1\nSTATUS=running");
}

int64_t NodeRuntime::NextTimerDue() const {
  int64_t due = std::numeric_limits<int64_t>::max();
  for (const Timer& t : timers_)
    if (t.scheduled) due = std::min(due, t.next_due);
  return due;
}

void NodeRuntime::FireDueTimers(int64_t now) {
  while (!StopRequested()) {
    // The earliest due timer first; ties go to the one added first (deterministic).
    Timer* next = nullptr;
    for (Timer& t : timers_)
      if (t.scheduled && t.next_due <= now && (next == nullptr || t.next_due < next->next_due)) next = &t;
    if (next == nullptr) return;
    if (batch()) {
      if (now - next->next_due > kMaxCatchUpPeriods * next->period_us) {
        const int64_t skipped = (now - next->next_due) / next->period_us;
        next->next_due += skipped * next->period_us;
        MINENAV_LOG(kWarn) << "log gap: a timer skipped " << skipped << " periods";
      }
      const int64_t due = next->next_due;
      batch_clock_.Set(std::max(batch_clock_.NowUtime(), due));
      next->next_due += next->period_us;
      next->callback(due);
    } else {
      next->next_due += next->period_us;
      // Fell behind (slow handler, suspended process): skip the missed periods.
      if (next->next_due <= now) next->next_due = now + next->period_us;
      next->callback(now);
    }
  }
}

int NodeRuntime::SpinOnce(int64_t max_wait_us) {
  Bus& b = bus();
  if (!started_) BeginClock(clock_->NowUtime());
  FireDueTimers(clock_->NowUtime());
  if (StopRequested()) return 0;
  int64_t wait = std::max<int64_t>(0, max_wait_us);
  const int64_t due = NextTimerDue();
  if (due != std::numeric_limits<int64_t>::max())
    wait = std::clamp<int64_t>(due - clock_->NowUtime(), 0, wait);
  return b.HandleFor(wait);
}

int NodeRuntime::RunLive() {
  while (!StopRequested()) {
    if (started_ && options_.run_for > 0 &&
        clock_->NowUtime() - start_utime_ >= SecondsToUs(options_.run_for))
      break;
    SpinOnce(kMaxWaitUs);
  }
  return 0;
}

int NodeRuntime::RunBatch() {
  const int64_t run_for_us = SecondsToUs(options_.run_for);
  bool reached_end = false;
  while (!StopRequested()) {
    std::optional<int64_t> ts;
    try {
      ts = log_bus_->PeekTimestamp();
    } catch (const InputError& e) {
      // A damaged log: what was read so far is kept as partial, and the run fails.
      interrupted_ = true;
      MINENAV_LOG(kError) << e.what() << " (after " << log_bus_->events_dispatched()
                          << " events: outputs are kept as partial)";
      return kExitUsage;
    }
    if (!ts) {
      reached_end = true;
      break;
    }
    const int64_t t = std::max(batch_clock_.NowUtime(), *ts);
    if (!started_) {
      batch_clock_.Set(t);
      BeginClock(t);
    }
    if (run_for_us > 0 && t - start_utime_ > run_for_us) break;
    FireDueTimers(t);
    batch_clock_.Set(t);
    log_bus_->DispatchNext();
  }
  if (!reached_end && StopSignalled()) {
    interrupted_ = true;
    MINENAV_LOG(kWarn) << "interrupted after " << log_bus_->events_dispatched() << " of the log's events ("
                       << bus_->counters().messages_in << " handled): outputs are kept as partial";
    return kExitInterrupted;
  }
  MINENAV_LOG(kInfo) << "batch done: " << log_bus_->events_dispatched() << " events, "
                     << bus_->counters().messages_in << " handled, " << bus_->counters().messages_bad
                     << " bad";
  return 0;
}

int NodeRuntime::Run() {
  bus();  // throws if not started
  InstallSignalHandlers();
  try {
    const int code = batch() ? RunBatch() : RunLive();
    Shutdown();
    return code;
  } catch (const std::exception& e) {
    status_message_ = e.what();
    try {
      PublishHeartbeat(heartbeat_t::ERROR);
    } catch (...) {
    }
    throw;
  }
}

std::string ExitSummary(const Bus& bus) {
  const BusCounters& c = bus.counters();
  std::string line = "stopping: " + std::to_string(c.messages_in) + " message(s) handled, " +
                     std::to_string(c.messages_bad) + " bad, " + std::to_string(c.published) + " published";
  if (c.stamps_rejected > 0) line += "; rejected for their timestamps: " + std::to_string(c.stamps_rejected);
  if (!bus.auth_rejected_by_channel().empty()) {
    line += "; refused by authentication:";
    for (const auto& [channel, count] : bus.auth_rejected_by_channel()) {
      line += " " + channel + " " + std::to_string(count);
    }
  }
  return line;
}

void NodeRuntime::Shutdown() {
  if (shut_down_ || bus_ == nullptr) return;
  shut_down_ = true;
  NotifyService("STOPPING=1");
  MINENAV_LOG(kInfo) << ExitSummary(*bus_);
  for (auto& hook : shutdown_hooks_) hook();
  if (options_.heartbeat_period > 0) PublishHeartbeat(heartbeat_t::STOPPING);
  if (log_bus_ != nullptr) {
    if (interrupted_) {
      log_bus_->CloseIncomplete();
    } else {
      log_bus_->Close();
    }
  }
}

int RunNodeMain(const std::string& process, const std::function<int()>& body) {
  SetLogProgramName(process);
  try {
    return body();
  } catch (const UsageError& e) {
    MINENAV_LOG(kError) << e.what();
    return kExitUsage;
  } catch (const InputError& e) {
    MINENAV_LOG(kError) << e.what();
    return kExitUsage;
  } catch (const std::exception& e) {
    MINENAV_LOG(kError) << e.what();
    return kExitRuntime;
  }
}

int RunNodeProcess(const std::string& process, const std::string& summary, std::vector<std::string>& args,
                   const std::function<void(ConfigSchema&)>& declare, const std::function<int(NodeRuntime&)>& run) {
  return RunNodeMain(process, [&] {
    ConfigSchema schema(process, summary);
    NodeRuntime runtime(process, schema);
    declare(schema);
    schema.AddHelpEpilog("Exit codes: 0 ok, 2 bad flag or input file, 3 runtime failure.\n");
    if (schema.Parse(args) == ParseOutcome::kExit) return 0;
    return run(runtime);
  });
}

int RunNodeProcess(const std::string& process, const std::string& summary, int argc, const char* const* argv,
                   const std::function<void(ConfigSchema&)>& declare, const std::function<int(NodeRuntime&)>& run) {
  std::vector<std::string> args(argv + (argc > 0 ? 1 : 0), argv + argc);
  return RunNodeProcess(process, summary, args, declare, run);
}

}  // namespace minenav
