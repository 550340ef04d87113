#include "viewer/log_replay.h"

#include <algorithm>
#include <map>
#include <utility>

#include "common/node/conversions.h"
#include "logger/message_catalog.h"
#include "minenav/heartbeat_t.hpp"

namespace minenav {

LogReplay::LogReplay(const std::string& path) {
  LogReader reader(path);
  while (auto e = reader.Next()) events_.push_back(std::move(*e));
  Index();
}

LogReplay::LogReplay(std::vector<LogEvent> events) : events_(std::move(events)) { Index(); }

void LogReplay::Index() {
  int64_t last = events_.empty() ? 0 : events_.front().timestamp;
  for (LogEvent& e : events_) {
    e.timestamp = std::max(e.timestamp, last);
    last = e.timestamp;
    bytes_ += static_cast<int64_t>(e.data.size());
    const MessageProbe probe = ProbeMessage(e.channel, e.data.data(), e.data.size());
    std::string key = e.channel;
    if (probe.ok && probe.type_name == "minenav.heartbeat_t") {
      heartbeat_t h{};
      std::string error;
      if (DecodeMessage(e.data.data(), static_cast<int>(e.data.size()), e.channel, &h, &error))
        key += "/" + h.process + "/" + h.instance;
    }
    keys_.push_back(std::move(key));
    track_.push_back(probe.ok && probe.type_name == "minenav.pose_estimate_t");
  }
}

std::vector<size_t> LogReplay::Seek(int64_t t) const {
  std::map<std::string, size_t> latest;
  std::vector<size_t> out;
  for (size_t i = 0; i < events_.size() && events_[i].timestamp <= t; ++i) {
    if (track_[i]) {
      out.push_back(i);
    } else {
      latest[keys_[i]] = i;
    }
  }
  for (const auto& [key, i] : latest) out.push_back(i);
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<size_t> LogReplay::Between(int64_t a, int64_t b) const {
  const auto by_time = [](const LogEvent& e, int64_t t) { return e.timestamp < t; };
  auto it = std::lower_bound(events_.begin(), events_.end(), a + 1, by_time);
  std::vector<size_t> out;
  for (; it != events_.end() && it->timestamp <= b; ++it) out.push_back(static_cast<size_t>(it - events_.begin()));
  return out;
}

}  // namespace minenav
