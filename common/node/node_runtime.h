#pragma once
// What every process of the fleet shares (DESIGN.md, "The fleet" and "The bus"): the
// common options, the bus (live LCM, or batch over a log with --log), the clock (wall
// clock live; in batch the time of the log, so timers fire deterministically at message
// time), periodic timers, HEARTBEAT, the handle loop, clean shutdown on SIGINT/SIGTERM,
// and exit codes. A process is a main that declares its options, subscribes, adds
// timers and calls Run(); see common/node/README.md for a complete example.
//
// Time in batch mode: the clock is a ManualClock set to each event's log timestamp (the
// receive time lcm-logger recorded, or the message utime for logs written by our tools)
// before the event is dispatched. A timer due between two events fires with the clock
// set to its due time, so a batch run over a log is repeatable bit for bit, and
// replaying the log with lcm-logplayer through the live process paces timers the same
// way.
//
// Under systemd (a Type=notify unit, fleet/README.md "systemd on a vehicle") a live node
// speaks the notify protocol through libsystemd: READY=1 when its loop starts, WATCHDOG=1
// from the loop at half the unit's WatchdogSec (so a loop that hangs is killed and
// restarted), STATUS= with its heartbeat's state and message, STOPPING=1 at shutdown.
// Without $NOTIFY_SOCKET (every run outside systemd) none of this does anything; batch
// runs never notify.

#include <csignal>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/clock.h"
#include "common/config.h"
#include "common/node/auth_bus.h"
#include "common/node/bus.h"

namespace minenav {

class LogBus;

// The options every process has. Flags use dashes (--lcm-url), config files underscores.
struct NodeOptions {
  std::string lcm_url;               // "" = $LCM_DEFAULT_URL, else kDefaultLcmUrl
  std::string log;                   // batch: read this LCM log instead of the bus
  std::string log_out;               // batch: write publications to this LCM log
  double heartbeat_period = 1.0;     // s between HEARTBEAT messages; 0 = none
  std::string log_level = "info";    // debug, info, warn, error
  int queue_capacity = 1000;         // messages each subscription buffers (live)
  double run_for = 0.0;              // s of clock time to run; 0 = until stopped / end of log
  std::string instance;              // distinguishes several copies of a process
  std::string heartbeat_channel = "HEARTBEAT";
  // s: messages stamped more than this after they were received (or before 0) are
  // rejected as bad (Bus::AcceptStamp); covers clock skew between hosts. 0 = no check.
  double max_stamp_lead = 10.0;
  // Signed command channels (auth_bus.h): --auth.key-file, --auth.signed-channels, --auth.max-age.
  AuthOptions auth;
};

// Shortest HEARTBEAT period accepted (s): a heartbeat carries counters, not data.
inline constexpr double kMinHeartbeatPeriod = 0.01;

class NodeRuntime {
 public:
  using TimerCallback = std::function<void(int64_t utime)>;

  // Registers the common options into `schema` (parse it before Start()).
  NodeRuntime(std::string process, ConfigSchema& schema);
  // Without a schema (tests, tools that parse their own flags).
  NodeRuntime(std::string process, NodeOptions options);
  ~NodeRuntime();
  NodeRuntime(const NodeRuntime&) = delete;
  NodeRuntime& operator=(const NodeRuntime&) = delete;

  // Validates the options and makes the bus: LogBus when --log is given, else LcmBus.
  // Throws UsageError (bad option), InputError (unreadable log) or std::runtime_error
  // (LCM cannot start).
  void Start();
  // Runs the live loop on `bus` and `clock` instead (tests: FakeBus + ManualClock).
  void StartWith(std::unique_ptr<Bus> bus, Clock& clock);

  Bus& bus();
  const Clock& clock() const { return *clock_; }
  int64_t NowUtime() const { return clock_->NowUtime(); }
  bool batch() const { return log_bus_ != nullptr; }
  LogBus* log_bus() { return log_bus_; }  // null when live
  const NodeOptions& options() const { return options_; }
  const std::string& process() const { return process_; }

  // Calls `callback(utime)` every `period_s` seconds of clock time, the first time as
  // soon as the clock is known (start of Run live; first event of the log in batch).
  // Live, a timer that fell behind skips the missed periods; in batch every period
  // fires, in order, with the clock set to its due time. Timers due at the same time
  // fire in the order they were added. Returns the timer's index.
  int AddTimer(double period_s, TimerCallback callback);

  // State and one-line message carried by the next heartbeats (heartbeat_t::OK, WARN, ...).
  void SetStatus(int8_t state, std::string message);
  // Called once at shutdown, before the STOPPING heartbeat (flush outputs here).
  void OnShutdown(std::function<void()> hook);

  // Runs until the end of the log (batch), SIGINT/SIGTERM, RequestStop() or --run-for,
  // then shuts down. Returns the exit code (0, or kExitInterrupted for a batch run stopped
  // by a signal before the end of its log). Exceptions from handlers are counted as
  // bad messages; an exception from a timer publishes an ERROR heartbeat and propagates.
  int Run();
  // One pass of the live loop: fires due timers, then handles messages for at most
  // max_wait_us (less if a timer is due sooner). Returns the messages dispatched.
  int SpinOnce(int64_t max_wait_us);
  // Publishes a STOPPING heartbeat, runs the shutdown hooks and closes the batch output
  // log (left as FILE.partial when interrupted()). Idempotent; Run() calls it.
  void Shutdown();

  void RequestStop() { stop_requested_ = true; }
  bool StopRequested() const;
  // True once a batch run ended before the end of its log (set before the shutdown hooks
  // run, so they can write what was done under names that say partial): SIGINT/SIGTERM
  // (Run() returns kExitInterrupted), or damage in the log (Run() returns kExitUsage
  // after one line naming the byte offset). Live, a signal is the normal way to stop.
  bool interrupted() const { return interrupted_; }
  // True once SIGINT or SIGTERM arrived (any runtime in the process). Safe to poll from a
  // worker thread or to hand to a long computation as its "should stop" test.
  static bool StopSignalled();
  // SIGINT and SIGTERM request a stop of every runtime in the process.
  static void InstallSignalHandlers();
  // Forgets a received SIGINT/SIGTERM (tests that signal themselves).
  static void ClearStopSignal();

  void PublishHeartbeat(int8_t state);
  int64_t heartbeats_published() const { return heartbeat_seq_; }
  // The watchdog period systemd asked for ($WATCHDOG_USEC), 0 when none; the loop sends
  // WATCHDOG=1 at half of it.
  int64_t watchdog_usec() const { return watchdog_usec_; }

 private:
  struct Timer {
    int64_t period_us = 0;
    int64_t next_due = 0;
    bool scheduled = false;
    TimerCallback callback;
  };
  void Register(ConfigSchema& schema);
  void ApplyLogSettings();
  // Wraps bus_ in an AuthBus when --auth.key-file is given (the one place authentication is wired).
  void WrapAuthentication();
  void BeginClock(int64_t utime);
  // systemd's notify protocol (live only; nothing without $NOTIFY_SOCKET).
  void StartServiceWatchdog();
  void NotifyService(const std::string& state) const;
  void FireDueTimers(int64_t now);
  int64_t NextTimerDue() const;
  int RunLive();
  int RunBatch();

  std::string process_;
  NodeOptions options_;
  std::unique_ptr<Bus> bus_;
  LogBus* log_bus_ = nullptr;
  WallClock wall_clock_;
  ManualClock batch_clock_;
  Clock* clock_ = &wall_clock_;
  std::vector<Timer> timers_;
  std::vector<std::function<void()>> shutdown_hooks_;
  bool started_ = false;  // the clock is known, timers are scheduled
  int64_t start_utime_ = 0;
  bool stop_requested_ = false;
  bool interrupted_ = false;
  bool shut_down_ = false;
  int8_t state_;
  std::string status_message_;
  int64_t heartbeat_seq_ = 0;
  int64_t stamps_rejected_at_last_heartbeat_ = 0;
  int64_t auth_rejected_at_last_heartbeat_ = 0;
  int64_t watchdog_usec_ = 0;
  std::string last_service_status_;
};

// The line a process logs when it stops: what its bus handled, refused and published, with the
// messages refused by authentication per channel ("...; refused by authentication: DRIVE_COMMAND
// 12 CUTTER_COMMAND 3"), which tests/bus/mission_test.sh compares with what an attacker sent.
std::string ExitSummary(const Bus& bus);

// Runs a process's main body: one-line error and exit code 2 for UsageError and
// InputError (bad flags, config or input files), 3 for any other failure.
int RunNodeMain(const std::string& process, const std::function<int()>& body);

// A process's main in one call, under RunNodeMain: a schema with the common options (the
// runtime's) and the process's own (`declare`), the exit codes appended to --help, the
// command line parsed (--help, --print-config, --print-options-table: exit 0), then `run`
// with the runtime not yet started (it validates, loads, calls runtime.Start() and wires its
// node). `args` (without argv[0]) are read after `declare`, which may take flags out of them.
int RunNodeProcess(const std::string& process, const std::string& summary, std::vector<std::string>& args,
                   const std::function<void(ConfigSchema&)>& declare, const std::function<int(NodeRuntime&)>& run);
int RunNodeProcess(const std::string& process, const std::string& summary, int argc, const char* const* argv,
                   const std::function<void(ConfigSchema&)>& declare, const std::function<int(NodeRuntime&)>& run);

}  // namespace minenav
