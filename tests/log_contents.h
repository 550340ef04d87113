#pragma once
// Reading what a run left in an LCM log, typed, for tests.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/node/conversions.h"
#include "common/node/event_log.h"

namespace minenav::testing {

template <typename T>
struct Logged {
  int64_t timestamp = 0;  // event timestamp, us
  T msg;
};

// Every event on `channel`, decoded as T; throws std::runtime_error naming the event if
// one does not decode.
template <typename T>
std::vector<Logged<T>> ReadChannel(const std::string& log_path, const std::string& channel) {
  std::vector<Logged<T>> out;
  LogReader reader(log_path);
  while (const LogEvent* e = reader.NextInPlace()) {
    if (e->channel != channel) continue;
    Logged<T> item;
    item.timestamp = e->timestamp;
    std::string error;
    if (!DecodeMessage(e->data.data(), static_cast<int>(e->data.size()), channel, &item.msg, &error))
      throw std::runtime_error(log_path + " event " + std::to_string(e->eventnum) + ": " + error);
    out.push_back(std::move(item));
  }
  return out;
}

// The raw payloads on `channel`, in file order.
inline std::vector<std::vector<uint8_t>> ReadPayloads(const std::string& log_path, const std::string& channel) {
  std::vector<std::vector<uint8_t>> out;
  LogReader reader(log_path);
  while (const LogEvent* e = reader.NextInPlace())
    if (e->channel == channel) out.push_back(e->data);
  return out;
}

}  // namespace minenav::testing
