#pragma once
// A recorded log as the operator's view replays it with a time slider (viewer_bridge
// --replay LOG): the whole log in memory, in time order, and the two questions the slider
// asks. Seek(t): what the page needs to show the moment t from nothing (the latest message
// of each channel up to t, of each process on HEARTBEAT, and every pose for the driven
// track). Between(a, b): the messages of (a, b], to play on from there.

#include <cstdint>
#include <string>
#include <vector>

#include "common/node/event_log.h"

namespace minenav {

class LogReplay {
 public:
  // Reads the whole log (LogReader: damage is an InputError naming the byte offset).
  // Events stamped earlier than the one before are kept at that one's time (file order wins).
  explicit LogReplay(const std::string& path);
  // The same from events already read (tests).
  explicit LogReplay(std::vector<LogEvent> events);

  int64_t start_utime() const { return events_.empty() ? 0 : events_.front().timestamp; }
  int64_t end_utime() const { return events_.empty() ? 0 : events_.back().timestamp; }
  size_t size() const { return events_.size(); }
  int64_t bytes() const { return bytes_; }

  // Indexes (into events()) of what shows the moment t, in time order.
  std::vector<size_t> Seek(int64_t t) const;
  // Indexes of the events with a < timestamp <= b.
  std::vector<size_t> Between(int64_t a, int64_t b) const;
  const LogEvent& event(size_t i) const { return events_[i]; }

 private:
  void Index();

  std::vector<LogEvent> events_;
  std::vector<std::string> keys_;  // what an event replaces: its channel, or channel/process/instance
  std::vector<bool> track_;        // events kept whole for the track (pose_estimate_t channels)
  int64_t bytes_ = 0;
};

}  // namespace minenav
