#include "coordinator/heartbeat_watch.h"

#include <cmath>
#include <cstdio>
#include <utility>

namespace minenav {

HeartbeatWatch::HeartbeatWatch(std::vector<std::string> required, double timeout_s)
    : required_(std::move(required)), timeout_us_(std::llround(timeout_s * 1e6)) {}

void HeartbeatWatch::OnHeartbeat(const HeartbeatSample& sample) {
  const HeartbeatRecord* before = monitor_.Find(sample.process, sample.instance);
  if (before && before->last.pid != sample.pid) {
    const std::string whole = sample.instance.empty() ? sample.process : sample.process + "/" + sample.instance;
    for (const std::string& p : required_)
      if (p == sample.process || p == whole) {
        restarts_.push_back(whole + " (pid " + std::to_string(sample.pid) + ", was " +
                            std::to_string(before->last.pid) + ")");
        break;
      }
  }
  monitor_.Add(sample);
}

const HeartbeatRecord* HeartbeatWatch::Latest(const std::string& process) const {
  const size_t slash = process.find('/');
  if (slash != std::string::npos) return monitor_.Find(process.substr(0, slash), process.substr(slash + 1));
  const HeartbeatRecord* best = nullptr;
  for (const HeartbeatRecord* r : monitor_.All())
    if (r->last.process == process && (!best || r->last.received > best->last.received)) best = r;
  return best;
}

std::string HeartbeatWatch::Why(const std::string& process, int64_t now) const {
  const HeartbeatRecord* r = Latest(process);
  if (!r) return "never seen";
  const HeartbeatSample& hb = r->last;
  if (now - hb.received > timeout_us_) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "no heartbeat for %.1f s", r->age_s(now));
    return buf;
  }
  if (hb.state == HeartbeatState::kOk || hb.state == HeartbeatState::kWarn) return "";
  return std::string(ToString(hb.state)) + (hb.message.empty() ? "" : " (" + hb.message + ")");
}

std::vector<std::string> HeartbeatWatch::NotReady(int64_t now) const {
  std::vector<std::string> out;
  for (const std::string& p : required_) {
    const std::string why = Why(p, now);
    if (!why.empty()) out.push_back(p + ": " + why);
  }
  return out;
}

}  // namespace minenav
