#pragma once
// The supervision of a fleet as a state machine (fleet/README.md, "Supervision"): which
// process to start now (its `after` ready, or its restart delay over), what an exit means
// (restart with backoff, crash loop given up, ended), readiness from HEARTBEAT, when the
// whole fleet must stop, and the status of every process. Pure: no processes, no bus, no
// clock; the node (supervisor_node.h) starts and signals processes and hands in what happened
// with the time it happened, so every rule is tested on a fake clock.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "fleet/fleet_file.h"
#include "common/heartbeat_monitor.h"
#include "fleet/restart_policy.h"

namespace minenav {

enum class ProcessState {
  kWaiting,     // not started yet: waits for the processes it comes after
  kStarting,    // started, not ready yet (ready = heartbeat or ok)
  kRunning,     // started and ready
  kRestarting,  // exited, restarts at its restart time
  kStopping,    // signalled by the supervisor, not exited yet
  kExited,      // ended for good: its restart policy does not restart it
  kGivenUp,     // a crash loop: no more restarts
  kStopped,     // stopped by the supervisor when the fleet stopped
};
const char* ToString(ProcessState state);

// One row of the status table.
struct ProcessStatus {
  std::string name;
  std::string group;
  ProcessState state = ProcessState::kWaiting;
  std::string state_text;  // "running", "restarting in 1.5 s", "given up: ...", "exited 0", ...
  int pid = 0;             // 0 when not running
  int restarts = 0;        // starts after the first
  std::optional<HeartbeatRecord> heartbeat;  // the last one heard from it, if any
};

// Something the node must do now.
struct SupervisorAction {
  enum class Kind { kStart, kStop };
  Kind kind = Kind::kStart;
  size_t process = 0;  // index into fleet().processes
};

// Why the fleet stops by itself, and the supervisor's exit code.
struct FleetEnd {
  int exit_code = 0;
  std::string reason;
};

class Supervisor {
 public:
  Supervisor(FleetSpec fleet, RestartOptions options);

  const FleetSpec& fleet() const { return fleet_; }

  // Starts due at `now` (first starts whose `after` are ready, restarts whose delay is
  // over) and stops (a process not ready within its ready_timeout). None once stopping.
  std::vector<SupervisorAction> Tick(int64_t now);
  // The node started process `i` (pid), or could not (a failure like an exit).
  void OnStarted(size_t i, int pid, int64_t now);
  void OnStartFailed(size_t i, const std::string& why, int64_t now);
  // Process `i` ended.
  void OnExited(size_t i, const ExitStatus& status, int64_t now);
  // A HEARTBEAT heard on the bus (any process; those of the fleet make theirs ready).
  void OnHeartbeat(const HeartbeatSample& sample);

  // From now on nothing starts; the node signals the running processes. Returns the
  // processes to signal (marked stopping).
  std::vector<size_t> BeginStop(const std::string& reason);
  bool stopping() const { return stopping_; }
  // Set once the fleet must stop by itself: a required process given up or failed for
  // good (exit code 3), a process with ends_fleet ended (its exit code), or nothing left
  // to supervise (0 when every process ended with success, else 3).
  const std::optional<FleetEnd>& end() const { return end_; }
  // True when no process runs or is being stopped.
  bool NoneRunning() const;

  // One line per thing that happened since the last call, for the log.
  std::vector<std::string> TakeEvents();

  std::vector<ProcessStatus> Status(int64_t now) const;
  // "6 running, 1 restarting, 1 given up": the supervisor's own HEARTBEAT message.
  std::string Summary() const;
  // OK while nothing failed; WARN when a process is restarting, given up or failed.
  HeartbeatState Health() const;
  const HeartbeatMonitor& heartbeats() const { return heartbeats_; }

 private:
  struct Process {
    ProcessState state = ProcessState::kWaiting;
    int pid = 0;
    int starts = 0;
    int64_t started_at = 0;
    int64_t restart_at = 0;
    bool ever_ready = false;         // was ready once (a restart does not make it wait again)
    bool stopped_not_ready = false;  // stopped for its readiness: the exit is a failure
    bool failed = false;             // ended or given up after a failure
    std::string reason;              // of the last exit, give-up or stop
    FailureHistory failures;
  };

  bool Ready(const std::string& name) const;
  bool MatchesHeartbeat(size_t i, const HeartbeatSample& sample) const;
  void HandleEnd(size_t i, bool failed, const std::string& what, int64_t now);
  void EndFleetIfDone();
  void Event(std::string line) { events_.push_back(std::move(line)); }

  FleetSpec fleet_;
  RestartOptions options_;
  std::vector<Process> processes_;
  HeartbeatMonitor heartbeats_;
  bool stopping_ = false;
  std::optional<FleetEnd> end_;
  std::vector<std::string> events_;
};

}  // namespace minenav
