#include "fleet/supervisor.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "fleet/number_text.h"

namespace minenav {

namespace {

std::string Seconds(int64_t us) { return FixedText(static_cast<double>(std::max<int64_t>(0, us)) * 1e-6, 1) + " s"; }

bool Satisfies(Readiness readiness, HeartbeatState state) {
  switch (readiness) {
    case Readiness::kStarted: return true;
    case Readiness::kHeartbeat: return state == HeartbeatState::kOk || state == HeartbeatState::kWarn;
    case Readiness::kOk: return state == HeartbeatState::kOk;
    case Readiness::kExited: return false;  // an exit, not a heartbeat, makes it ready
  }
  return false;
}

}  // namespace

const char* ToString(ProcessState state) {
  switch (state) {
    case ProcessState::kWaiting: return "waiting";
    case ProcessState::kStarting: return "starting";
    case ProcessState::kRunning: return "running";
    case ProcessState::kRestarting: return "restarting";
    case ProcessState::kStopping: return "stopping";
    case ProcessState::kExited: return "exited";
    case ProcessState::kGivenUp: return "given up";
    case ProcessState::kStopped: return "stopped";
  }
  return "?";
}

Supervisor::Supervisor(FleetSpec fleet, RestartOptions options)
    : fleet_(std::move(fleet)), options_(options), processes_(fleet_.processes.size()) {}

bool Supervisor::Ready(const std::string& name) const {
  for (size_t i = 0; i < fleet_.processes.size(); ++i) {
    if (fleet_.processes[i].name != name) continue;
    const Process& p = processes_[i];
    // A one-shot step (ready = exited) is ready once it ended well; a process that ended
    // well did its job. One that was ready once and is restarting does not hold them back.
    if (p.state == ProcessState::kExited) return !p.failed;
    if (fleet_.processes[i].ready == Readiness::kExited) return false;
    return p.ever_ready && p.state != ProcessState::kGivenUp && p.state != ProcessState::kStopped;
  }
  return true;  // not in this fleet (another host's): nothing to wait for
}

std::vector<SupervisorAction> Supervisor::Tick(int64_t now) {
  std::vector<SupervisorAction> actions;
  if (stopping_) return actions;
  for (size_t i = 0; i < processes_.size(); ++i) {
    const ProcessSpec& spec = fleet_.processes[i];
    Process& p = processes_[i];
    if (p.state == ProcessState::kWaiting) {
      if (std::all_of(spec.after.begin(), spec.after.end(), [&](const std::string& d) { return Ready(d); }))
        actions.push_back({SupervisorAction::Kind::kStart, i});
    } else if (p.state == ProcessState::kRestarting && now >= p.restart_at) {
      actions.push_back({SupervisorAction::Kind::kStart, i});
    } else if (p.state == ProcessState::kStarting &&
               now - p.started_at >= static_cast<int64_t>(std::llround(spec.ready_timeout * 1e6))) {
      p.state = ProcessState::kStopping;
      p.stopped_not_ready = true;
      p.reason = std::string("not ready after ") + Seconds(now - p.started_at) + " (ready = " + ToString(spec.ready) +
                 ": no such HEARTBEAT from " + spec.heartbeat_process + ")";
      Event(spec.name + " " + p.reason + ": stopping it");
      actions.push_back({SupervisorAction::Kind::kStop, i});
    }
  }
  return actions;
}

void Supervisor::OnStarted(size_t i, int pid, int64_t now) {
  Process& p = processes_.at(i);
  const ProcessSpec& spec = fleet_.processes[i];
  p.pid = pid;
  p.started_at = now;
  p.stopped_not_ready = false;
  ++p.starts;
  p.state = spec.ready == Readiness::kStarted ? ProcessState::kRunning : ProcessState::kStarting;
  if (p.state == ProcessState::kRunning) p.ever_ready = true;
  Event((p.starts == 1 ? "started " : "restarted ") + spec.name + " (pid " + std::to_string(pid) +
        (p.starts == 1 ? "" : ", restart " + std::to_string(p.starts - 1)) + ")");
}

void Supervisor::OnStartFailed(size_t i, const std::string& why, int64_t now) {
  Process& p = processes_.at(i);
  ++p.starts;
  p.started_at = now;
  p.pid = 0;
  HandleEnd(i, /*failed=*/true, "could not start: " + why, now);
}

void Supervisor::OnExited(size_t i, const ExitStatus& status, int64_t now) {
  Process& p = processes_.at(i);
  const ProcessSpec& spec = fleet_.processes[i];
  p.pid = 0;
  if (p.state == ProcessState::kStopping && !p.stopped_not_ready) {
    p.state = ProcessState::kStopped;
    p.reason = Describe(status);
    Event("stopped " + spec.name + " (" + p.reason + ")");
    EndFleetIfDone();
    return;
  }
  const bool failed = p.stopped_not_ready || !status.success();
  HandleEnd(i, failed, p.stopped_not_ready ? p.reason + ", then " + Describe(status) : Describe(status), now);
}

void Supervisor::HandleEnd(size_t i, bool failed, const std::string& what, int64_t now) {
  Process& p = processes_[i];
  const ProcessSpec& spec = fleet_.processes[i];
  p.stopped_not_ready = false;
  if (stopping_) {  // it ended by itself while the fleet stops: no restart
    p.state = ProcessState::kStopped;
    p.reason = what;
    Event(spec.name + " ended while stopping: " + what);
    EndFleetIfDone();
    return;
  }
  const AfterExit after = DecideAfterExit(spec.restart, options_, p.failures, p.started_at, now, failed, what);
  p.reason = after.reason;
  p.failed = failed;
  switch (after.kind) {
    case AfterExit::Kind::kRestart:
      p.state = ProcessState::kRestarting;
      p.restart_at = after.restart_at;
      Event(spec.name + " " + after.reason);
      break;
    case AfterExit::Kind::kGiveUp:
      p.state = ProcessState::kGivenUp;
      Event(spec.name + " GIVEN UP: " + after.reason + "; no more restarts");
      break;
    case AfterExit::Kind::kEnded:
      p.state = ProcessState::kExited;
      Event(spec.name + " ended: " + after.reason + (failed ? " (restart = " + std::string(ToString(spec.restart)) + ")" : ""));
      break;
  }
  const bool for_good = p.state == ProcessState::kGivenUp || p.state == ProcessState::kExited;
  if (for_good && !end_) {
    if (spec.required && failed) {
      end_ = FleetEnd{kExitRuntime, "required process " + spec.name + " " +
                                        (p.state == ProcessState::kGivenUp ? "given up: " : "failed: ") + p.reason};
    } else if (spec.ends_fleet) {
      end_ = FleetEnd{failed ? kExitRuntime : 0, spec.name + " ended (" + p.reason + "), and it ends the fleet"};
    }
  }
  EndFleetIfDone();
}

// Nothing left to run or to wait for: the fleet is over.
void Supervisor::EndFleetIfDone() {
  if (end_ || stopping_) return;
  bool any_failed = false;
  for (size_t i = 0; i < processes_.size(); ++i) {
    const Process& p = processes_[i];
    if (p.state != ProcessState::kExited && p.state != ProcessState::kGivenUp) {
      // A waiting process whose predecessor failed for good will never start.
      if (p.state != ProcessState::kWaiting) return;
      const ProcessSpec& spec = fleet_.processes[i];
      const bool blocked = std::any_of(spec.after.begin(), spec.after.end(), [&](const std::string& d) {
        for (size_t j = 0; j < processes_.size(); ++j)
          if (fleet_.processes[j].name == d)
            return processes_[j].failed &&
                   (processes_[j].state == ProcessState::kExited || processes_[j].state == ProcessState::kGivenUp);
        return false;
      });
      if (!blocked) return;
    }
    any_failed = any_failed || p.failed || p.state == ProcessState::kWaiting;
  }
  end_ = FleetEnd{any_failed ? kExitRuntime : 0,
                  any_failed ? "nothing left to supervise: every process ended, not all of them well"
                             : "nothing left to supervise: every process ended well"};
}

bool Supervisor::MatchesHeartbeat(size_t i, const HeartbeatSample& sample) const {
  const ProcessSpec& spec = fleet_.processes[i];
  return spec.has_heartbeat() && spec.heartbeat_process == sample.process && spec.heartbeat_instance == sample.instance;
}

void Supervisor::OnHeartbeat(const HeartbeatSample& sample) {
  heartbeats_.Add(sample);
  for (size_t i = 0; i < processes_.size(); ++i) {
    Process& p = processes_[i];
    if (p.state != ProcessState::kStarting || !MatchesHeartbeat(i, sample)) continue;
    // Only this run's heartbeats count (not a late one from the run before a restart).
    if (sample.received < p.started_at) continue;
    if (Satisfies(fleet_.processes[i].ready, sample.state)) {
      p.state = ProcessState::kRunning;
      p.ever_ready = true;
      Event(fleet_.processes[i].name + " ready (HEARTBEAT " + ToString(sample.state) + ")");
    }
  }
}

std::vector<size_t> Supervisor::BeginStop(const std::string& reason) {
  std::vector<size_t> to_signal;
  if (!stopping_) Event("stopping the fleet: " + reason);
  stopping_ = true;
  for (size_t i = 0; i < processes_.size(); ++i) {
    Process& p = processes_[i];
    if (p.state == ProcessState::kStarting || p.state == ProcessState::kRunning) {
      p.state = ProcessState::kStopping;
      to_signal.push_back(i);
    } else if (p.state == ProcessState::kStopping) {
      p.stopped_not_ready = false;  // its exit is now part of the fleet's stop
      to_signal.push_back(i);
    } else if (p.state == ProcessState::kWaiting || p.state == ProcessState::kRestarting) {
      p.reason = p.state == ProcessState::kWaiting ? "never started" : "not restarted";
      p.state = ProcessState::kStopped;
    }
  }
  return to_signal;
}

bool Supervisor::NoneRunning() const {
  return std::none_of(processes_.begin(), processes_.end(), [](const Process& p) {
    return p.state == ProcessState::kStarting || p.state == ProcessState::kRunning || p.state == ProcessState::kStopping;
  });
}

std::vector<std::string> Supervisor::TakeEvents() {
  std::vector<std::string> out;
  out.swap(events_);
  return out;
}

std::vector<ProcessStatus> Supervisor::Status(int64_t now) const {
  std::vector<ProcessStatus> rows;
  for (size_t i = 0; i < processes_.size(); ++i) {
    const ProcessSpec& spec = fleet_.processes[i];
    const Process& p = processes_[i];
    ProcessStatus row;
    row.name = spec.name;
    row.group = spec.group;
    row.state = p.state;
    row.pid = p.pid;
    row.restarts = std::max(0, p.starts - 1);
    if (const HeartbeatRecord* hb = heartbeats_.Find(spec.heartbeat_process, spec.heartbeat_instance);
        hb != nullptr && spec.has_heartbeat())
      row.heartbeat = *hb;
    switch (p.state) {
      case ProcessState::kWaiting: {
        std::string waits;
        for (const std::string& d : spec.after)
          if (!Ready(d)) waits += (waits.empty() ? "" : ", ") + d;
        row.state_text = waits.empty() ? "starting now" : "waiting for " + waits;
        break;
      }
      case ProcessState::kStarting: row.state_text = std::string("starting (ready = ") + ToString(spec.ready) + ")"; break;
      case ProcessState::kRunning: row.state_text = "running"; break;
      case ProcessState::kRestarting: row.state_text = "restarting in " + Seconds(p.restart_at - now); break;
      case ProcessState::kStopping: row.state_text = "stopping"; break;
      case ProcessState::kExited: row.state_text = "exited: " + p.reason; break;
      case ProcessState::kGivenUp: row.state_text = "GIVEN UP: " + p.reason; break;
      case ProcessState::kStopped: row.state_text = p.reason.empty() ? "stopped" : "stopped (" + p.reason + ")"; break;
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

std::string Supervisor::Summary() const {
  std::map<ProcessState, int> counts;
  for (const Process& p : processes_) ++counts[p.state];
  std::string summary;
  for (const auto& [state, n] : counts) summary += (summary.empty() ? "" : ", ") + std::to_string(n) + " " + ToString(state);
  for (size_t i = 0; i < processes_.size(); ++i)
    if (processes_[i].state == ProcessState::kGivenUp) summary += "; " + fleet_.processes[i].name + " given up";
  return summary;
}

HeartbeatState Supervisor::Health() const {
  const bool trouble = std::any_of(processes_.begin(), processes_.end(), [](const Process& p) {
    return p.state == ProcessState::kRestarting || p.state == ProcessState::kGivenUp ||
           (p.state == ProcessState::kExited && p.failed);
  });
  return trouble ? HeartbeatState::kWarn : HeartbeatState::kOk;
}

}  // namespace minenav
