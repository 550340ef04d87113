#include "coordinator/heartbeat_watch.h"

#include <cmath>
#include <cstdio>
#include <utility>

namespace minenav {

const char* ToString(HeartbeatState s) {
  switch (s) {
    case HeartbeatState::kStarting: return "STARTING";
    case HeartbeatState::kOk: return "OK";
    case HeartbeatState::kWarn: return "WARN";
    case HeartbeatState::kError: return "ERROR";
    case HeartbeatState::kStopping: return "STOPPING";
  }
  return "UNKNOWN";
}

HeartbeatWatch::HeartbeatWatch(std::vector<std::string> required, double timeout_s)
    : required_(std::move(required)), timeout_us_(std::llround(timeout_s * 1e6)) {}

void HeartbeatWatch::OnHeartbeat(const HeartbeatInfo& hb) {
  latest_[hb.process] = hb;
  if (!hb.instance.empty()) latest_[hb.process + "/" + hb.instance] = hb;
}

double HeartbeatWatch::Age(const std::string& process, int64_t now) const {
  const auto it = latest_.find(process);
  return it == latest_.end() ? -1.0 : static_cast<double>(now - it->second.utime) * 1e-6;
}

std::string HeartbeatWatch::Why(const std::string& process, int64_t now) const {
  const auto it = latest_.find(process);
  if (it == latest_.end()) return "never seen";
  const HeartbeatInfo& hb = it->second;
  if (now - hb.utime > timeout_us_) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "no heartbeat for %.1f s", static_cast<double>(now - hb.utime) * 1e-6);
    return buf;
  }
  if (hb.state == HeartbeatState::kOk || hb.state == HeartbeatState::kWarn) return "";
  return std::string(ToString(hb.state)) + (hb.message.empty() ? "" : " (" + hb.message + ")");
}

bool HeartbeatWatch::Ready(const std::string& process, int64_t now) const { return Why(process, now).empty(); }

std::vector<std::string> HeartbeatWatch::NotReady(int64_t now) const {
  std::vector<std::string> out;
  for (const std::string& p : required_) {
    const std::string why = Why(p, now);
    if (!why.empty()) out.push_back(p + ": " + why);
  }
  return out;
}

}  // namespace minenav
