#pragma once
// Which processes of the fleet are alive (thesis 6.1: TCA's monitors; here HEARTBEAT). A
// process is ready when its latest heartbeat is OK or WARN (alive and working; WARN says
// something is wrong that the process handles itself, e.g. the tracker stopped on a stale
// pose) and came less than `timeout` ago; STARTING, ERROR, STOPPING or silence is not ready.
// Plain C++: the caller passes the clock.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace minenav {

// heartbeat_t's state constants.
enum class HeartbeatState : int8_t { kStarting = 0, kOk = 1, kWarn = 2, kError = 3, kStopping = 4 };
const char* ToString(HeartbeatState s);

struct HeartbeatInfo {
  std::string process;   // heartbeat_t.process
  std::string instance;  // "" if one
  HeartbeatState state = HeartbeatState::kOk;
  std::string message;
  int64_t utime = 0;     // us, when it was received
};

class HeartbeatWatch {
 public:
  // required: process names ("path_tracker"), or "name/instance" for one copy of several.
  HeartbeatWatch(std::vector<std::string> required, double timeout_s);

  void OnHeartbeat(const HeartbeatInfo& hb);

  bool Ready(const std::string& process, int64_t now) const;
  bool AllReady(int64_t now) const { return NotReady(now).empty(); }
  // The required processes that are not ready, with why, in the order required:
  // "path_tracker: no heartbeat for 3.2 s", "cutter: never seen", "contour_mapper: ERROR (disk full)".
  std::vector<std::string> NotReady(int64_t now) const;
  // Seconds since the process's last heartbeat, or -1 if never seen.
  double Age(const std::string& process, int64_t now) const;
  const std::vector<std::string>& required() const { return required_; }

 private:
  std::string Why(const std::string& process, int64_t now) const;  // "" when ready

  std::vector<std::string> required_;
  int64_t timeout_us_;
  std::map<std::string, HeartbeatInfo> latest_;  // by name and by name/instance
};

}  // namespace minenav
