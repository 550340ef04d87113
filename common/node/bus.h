#pragma once
// The message bus every process talks through, as an interface that can be mocked
// (after Drake's DrakeLcmInterface): raw Publish/Subscribe of bytes on a channel, plus
// typed helpers that encode/decode the generated LCM types. Implementations:
//   LcmBus   (lcm_bus.h)   live LCM over UDP multicast;
//   LogBus   (log_bus.h)   batch over an LCM event log, deterministic;
//   FakeBus  (fake_bus.h)  in-memory, for unit tests of nodes.
//
// Rules the typed helpers enforce (DESIGN.md, "Bad input"): a message that does not
// decode (wrong fingerprint, truncated) or that the node rejects (FromLcm throws
// InputError, or the handler throws anything) is counted in messages_bad and logged in
// one line naming the channel; it never crashes the process and no exception ever
// crosses LCM's C callbacks.

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "common/node/conversions.h"

namespace minenav {

// The default URL: ttl=0 keeps packets on this host; a 4 MB receive buffer keeps scans
// (about 8 KB each) from being dropped in bursts (DESIGN.md, "The bus").
inline constexpr const char* kDefaultLcmUrl =
    "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";

// `flag` if not empty, else $LCM_DEFAULT_URL if set, else kDefaultLcmUrl.
std::string ResolveLcmUrl(const std::string& flag);

// One received message. `data` is valid only during the handler call.
struct RawMessage {
  std::string_view channel;
  const uint8_t* data = nullptr;
  int size = 0;
  int64_t utime = 0;  // us: receive time (live) or the log event's timestamp (batch)
};
using RawHandler = std::function<void(const RawMessage&)>;

// Totals since the bus was made; they go into HEARTBEAT.
struct BusCounters {
  int64_t messages_in = 0;     // messages decoded and handled without error
  int64_t messages_bad = 0;    // messages that did not decode or were rejected
  int64_t published = 0;       // messages published
  int64_t publish_errors = 0;  // publications the transport refused
  int64_t stamps_rejected = 0; // of messages_bad: rejected for their utime (see AcceptStamp)
  int64_t auth_rejected = 0;   // of messages_bad: rejected by authentication (auth_bus.h)
};

class Bus {
 public:
  virtual ~Bus() = default;

  // Sends `size` bytes on `channel`. Returns false (and logs, counts) on failure.
  virtual bool Publish(const std::string& channel, const void* data, int size) = 0;

  // Calls `handler` for every message whose channel matches `channel`, an LCM channel
  // pattern (a regular expression implicitly anchored at both ends; plain names match
  // exactly). Handlers run on the thread that calls HandleFor, one at a time.
  virtual void Subscribe(const std::string& channel, RawHandler handler) = 0;

  // Waits up to timeout_us for messages and dispatches them. Returns the number of
  // messages dispatched (0 on timeout, or at the end of a log); throws on a transport
  // failure.
  virtual int HandleFor(int64_t timeout_us) = 0;

  // Called by the typed helpers (and by raw handlers that validate their own input).
  void CountHandled() { ++counters_.messages_in; }
  // Counts a bad message and logs `error` in one line (the first few per channel, then
  // every 1000th, so a stream of garbage cannot flood the log).
  void ReportBad(std::string_view channel, const std::string& error);
  const BusCounters& counters() const { return counters_; }
  // Why the latest message was rejected for its timestamp ("" if none yet), for HEARTBEAT.
  const std::string& last_stamp_rejection() const { return last_stamp_rejection_; }
  // Why the latest message was rejected by authentication ("" if none yet), for HEARTBEAT.
  const std::string& last_auth_rejection() const { return last_auth_rejection_; }

  // The timestamp window (DESIGN.md "The bus"; common/node/README.md "Limits"). A message
  // whose utime is negative, or more than max_lead_us after the time it was received (the
  // receive time live; the event's timestamp in a log), is rejected before its handler
  // runs: a scan stamped INT64_MAX would otherwise hold up the scan/odometry pairing, and
  // odometry stamped in the far future would reset its history. Stamps in the past are
  // allowed: lcm-logplayer replays old logs live. 0 (the default of a bare bus) = no check;
  // NodeRuntime sets it from --max-stamp-lead.
  void set_max_stamp_lead_us(int64_t max_lead_us) { max_stamp_lead_us_ = max_lead_us; }
  int64_t max_stamp_lead_us() const { return max_stamp_lead_us_; }
  // True when `stamp` passes the window; otherwise counts and logs it as bad and returns false.
  bool AcceptStamp(const RawMessage& raw, int64_t stamp, const char* type_name);
  // Bad messages per channel, for tests and for log_tool info.
  const std::map<std::string, int64_t, std::less<>>& bad_by_channel() const { return bad_by_channel_; }
  // Messages refused by authentication per channel (of bad_by_channel), for the exit summary.
  const std::map<std::string, int64_t, std::less<>>& auth_rejected_by_channel() const {
    return auth_rejected_by_channel_;
  }

 protected:
  void CountPublished(bool ok, const std::string& channel);
  // Counts a message refused by authentication (bad and auth_rejected) and logs `why`.
  void ReportUnauthenticated(std::string_view channel, const std::string& why);

 private:
  BusCounters counters_;
  std::map<std::string, int64_t, std::less<>> bad_by_channel_;
  std::map<std::string, int64_t, std::less<>> auth_rejected_by_channel_;
  std::string last_stamp_rejection_;
  std::string last_auth_rejection_;
  int64_t max_stamp_lead_us_ = 0;
};

// Encodes and publishes a generated LCM message.
template <typename T>
bool Publish(Bus& bus, const std::string& channel, const T& msg) {
  const std::vector<uint8_t> bytes = EncodeMessage(msg);
  return bus.Publish(channel, bytes.data(), static_cast<int>(bytes.size()));
}

// Subscribes with decoding. `handler` is callable as handler(const T&) or
// handler(const RawMessage&, const T&) (to see the channel or receive time).
// A message that fails to decode, whose utime is outside the bus's timestamp window
// (AcceptStamp), or whose handler throws (FromLcm throws InputError for invalid content),
// is counted in messages_bad and logged with its channel.
template <typename T, typename Handler>
void Subscribe(Bus& bus, const std::string& channel, Handler handler) {
  static_assert(std::is_invocable_v<Handler&, const T&> ||
                    std::is_invocable_v<Handler&, const RawMessage&, const T&>,
                "handler must take (const T&) or (const RawMessage&, const T&)");
  bus.Subscribe(channel, [&bus, handler = std::move(handler)](const RawMessage& raw) mutable {
    const std::string channel_name(raw.channel);
    T msg{};
    std::string error;
    if (!DecodeMessage(raw.data, raw.size, channel_name, &msg, &error)) {
      bus.ReportBad(raw.channel, error);
      return;
    }
    if constexpr (requires { msg.utime; }) {
      if (!bus.AcceptStamp(raw, msg.utime, T::getTypeName())) return;
    }
    try {
      if constexpr (std::is_invocable_v<Handler&, const RawMessage&, const T&>) {
        handler(raw, msg);
      } else {
        handler(msg);
      }
      bus.CountHandled();
    } catch (const std::exception& e) {
      bus.ReportBad(raw.channel, "channel " + channel_name + ": " + T::getTypeName() +
                                     " rejected: " + e.what());
    }
  });
}

// True when `pattern` (an LCM channel regex) matches `channel` in full. Plain names are
// compared without building a regex.
class ChannelMatcher {
 public:
  explicit ChannelMatcher(std::string pattern);
  bool Matches(std::string_view channel) const;
  const std::string& pattern() const { return pattern_; }

 private:
  std::string pattern_;
  bool literal_ = true;
  std::shared_ptr<const void> regex_;  // std::regex, kept out of this header
};

}  // namespace minenav
