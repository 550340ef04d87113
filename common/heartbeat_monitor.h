#pragma once
// What the HEARTBEATs on the bus say about each process: the last one, its age, and the
// rate of messages it handles (messages_in per second between two consecutive heartbeats
// of the same pid). Pure: the node hands in each heartbeat with its receive time.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace minenav {

// heartbeat_t's states (lcmtypes/heartbeat_t.lcm; this library links no LCM, the node
// checks at compile time that the numbers agree).
enum class HeartbeatState : int { kStarting = 0, kOk = 1, kWarn = 2, kError = 3, kStopping = 4 };
const char* ToString(HeartbeatState state);  // "STARTING", "OK", ...; "?" for another number

struct HeartbeatSample {
  int64_t received = 0;  // µs on the receiver's clock
  int64_t utime = 0;     // µs on the sender's clock (its stamp)
  std::string process;
  std::string instance;
  int pid = 0;
  HeartbeatState state = HeartbeatState::kStarting;
  std::string message;
  int64_t messages_in = 0;
  int64_t messages_bad = 0;
};

struct HeartbeatRecord {
  HeartbeatSample last;
  std::optional<double> messages_per_s;  // from the last two heartbeats of the same pid
  double age_s(int64_t now) const { return static_cast<double>(now - last.received) * 1e-6; }
};

class HeartbeatMonitor {
 public:
  void Add(const HeartbeatSample& sample);
  // The record of `process` (with `instance`), or null when none was heard.
  const HeartbeatRecord* Find(const std::string& process, const std::string& instance) const;
  void Forget(const std::string& process, const std::string& instance);
  // Every record, ordered by process then instance.
  std::vector<const HeartbeatRecord*> All() const;

 private:
  std::map<std::pair<std::string, std::string>, HeartbeatRecord> records_;
};

}  // namespace minenav
