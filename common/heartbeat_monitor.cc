#include "common/heartbeat_monitor.h"

namespace minenav {

const char* ToString(HeartbeatState state) {
  switch (state) {
    case HeartbeatState::kStarting: return "STARTING";
    case HeartbeatState::kOk: return "OK";
    case HeartbeatState::kWarn: return "WARN";
    case HeartbeatState::kError: return "ERROR";
    case HeartbeatState::kStopping: return "STOPPING";
  }
  return "?";
}

void HeartbeatMonitor::Add(const HeartbeatSample& sample) {
  HeartbeatRecord& record = records_[{sample.process, sample.instance}];
  const HeartbeatSample& previous = record.last;
  const bool consecutive = !previous.process.empty() && previous.pid == sample.pid &&
                           sample.utime > previous.utime && sample.messages_in >= previous.messages_in;
  if (consecutive) {
    record.messages_per_s = static_cast<double>(sample.messages_in - previous.messages_in) /
                            (static_cast<double>(sample.utime - previous.utime) * 1e-6);
  } else {
    record.messages_per_s.reset();  // a new process (restart) or a clock that went back
  }
  record.last = sample;
}

const HeartbeatRecord* HeartbeatMonitor::Find(const std::string& process, const std::string& instance) const {
  const auto it = records_.find({process, instance});
  return it == records_.end() ? nullptr : &it->second;
}

void HeartbeatMonitor::Forget(const std::string& process, const std::string& instance) {
  records_.erase({process, instance});
}

std::vector<const HeartbeatRecord*> HeartbeatMonitor::All() const {
  std::vector<const HeartbeatRecord*> all;
  for (const auto& [key, record] : records_) all.push_back(&record);
  return all;
}

}  // namespace minenav
