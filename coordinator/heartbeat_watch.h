#pragma once
// Which required processes of the fleet are ready (thesis 6.1: TCA's monitors; here HEARTBEAT),
// on the fleet's one record of heartbeats (common/heartbeat_monitor.h, which the supervisor
// uses too). A process is ready when its latest heartbeat is OK or WARN (alive and working;
// WARN says something is wrong that the process handles itself, e.g. the tracker stopped on a
// stale pose) and arrived less than `timeout` ago; STARTING, ERROR, STOPPING or silence is not
// ready. Plain C++: the caller passes the clock.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/heartbeat_monitor.h"

namespace minenav {

class HeartbeatWatch {
 public:
  // required: process names ("path_tracker": any instance), or "name/instance" for one copy.
  HeartbeatWatch(std::vector<std::string> required, double timeout_s);

  // A heartbeat with its receive time (sample.received, us on this clock). A required
  // process heard from a new pid has been restarted (by its supervisor, before its silence
  // could reach the timeout): it knows nothing of what it was doing.
  void OnHeartbeat(const HeartbeatSample& sample);
  // The restarts of required processes since the last call: "path_tracker (pid 812, was 640)".
  std::vector<std::string> TakeRestarts() { return std::exchange(restarts_, {}); }

  bool Ready(const std::string& process, int64_t now) const { return Why(process, now).empty(); }
  bool AllReady(int64_t now) const { return NotReady(now).empty(); }
  // The required processes that are not ready, with why, in the order required:
  // "path_tracker: no heartbeat for 3.2 s", "cutter: never seen", "contour_mapper: ERROR (disk full)".
  std::vector<std::string> NotReady(int64_t now) const;
  const std::vector<std::string>& required() const { return required_; }
  const HeartbeatMonitor& monitor() const { return monitor_; }

 private:
  // The freshest record of `process` ("name" or "name/instance"), or null.
  const HeartbeatRecord* Latest(const std::string& process) const;
  std::string Why(const std::string& process, int64_t now) const;  // "" when ready

  std::vector<std::string> required_;
  int64_t timeout_us_;
  HeartbeatMonitor monitor_;
  std::vector<std::string> restarts_;
};

}  // namespace minenav
