#include "common/node/heartbeat_conversion.h"

#include <string>

#include "common/file_io.h"

namespace minenav {

static_assert(static_cast<int>(HeartbeatState::kStarting) == heartbeat_t::STARTING &&
                  static_cast<int>(HeartbeatState::kOk) == heartbeat_t::OK &&
                  static_cast<int>(HeartbeatState::kWarn) == heartbeat_t::WARN &&
                  static_cast<int>(HeartbeatState::kError) == heartbeat_t::ERROR &&
                  static_cast<int>(HeartbeatState::kStopping) == heartbeat_t::STOPPING,
              "common/heartbeat_monitor.h mirrors heartbeat_t's states");

HeartbeatSample HeartbeatSampleFromLcm(const heartbeat_t& message, int64_t received) {
  if (message.state < heartbeat_t::STARTING || message.state > heartbeat_t::STOPPING)
    throw InputError("heartbeat_t.state " + std::to_string(message.state) + " from " + message.process + " is unknown");
  if (message.messages_in < 0 || message.messages_bad < 0)
    throw InputError("heartbeat_t from " + message.process + ": negative message counts");
  HeartbeatSample s;
  s.received = received;
  s.utime = message.utime;
  s.process = message.process;
  s.instance = message.instance;
  s.pid = message.pid;
  s.state = static_cast<HeartbeatState>(message.state);
  s.message = message.message;
  s.messages_in = message.messages_in;
  s.messages_bad = message.messages_bad;
  return s;
}

}  // namespace minenav
