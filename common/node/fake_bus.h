#pragma once
// An in-memory bus for unit tests of nodes: no network, no threads. Publications are
// recorded; Inject() queues a message that the next HandleFor() dispatches to matching
// subscribers (as LCM would, including to a node's own publications when loopback is on).
//
//   FakeBus bus;
//   Subscribe<minenav::odometry_t>(bus, "ODOMETRY", [&](const odometry_t& m) { ... });
//   bus.InjectMessage("ODOMETRY", msg, /*utime=*/1000);
//   bus.HandleFor(0);
//   EXPECT_EQ(bus.PublishedOn("POSE").size(), 1u);

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "common/node/bus.h"

namespace minenav {

class FakeBus final : public Bus {
 public:
  struct Message {
    std::string channel;
    std::vector<uint8_t> data;
    int64_t utime = 0;
  };

  bool Publish(const std::string& channel, const void* data, int size) override {
    const auto* bytes = static_cast<const uint8_t*>(data);
    published_.push_back({channel, std::vector<uint8_t>(bytes, bytes + size), 0});
    if (loopback_) pending_.push_back(published_.back());
    CountPublished(true, channel);
    return true;
  }

  void Subscribe(const std::string& channel, RawHandler handler) override {
    subscriptions_.push_back({ChannelMatcher(channel), std::move(handler)});
  }

  // Dispatches every queued message (the timeout is ignored). Returns how many.
  int HandleFor(int64_t /*timeout_us*/) override {
    int n = 0;
    while (!pending_.empty()) {
      const Message m = std::move(pending_.front());
      pending_.pop_front();
      RawMessage raw;
      raw.channel = m.channel;
      raw.data = m.data.data();
      raw.size = static_cast<int>(m.data.size());
      raw.utime = m.utime;
      for (auto& sub : subscriptions_) {
        if (!sub.matcher.Matches(raw.channel)) continue;
        try {
          sub.handler(raw);
        } catch (const std::exception& e) {
          ReportBad(raw.channel, "channel " + m.channel + ": handler failed: " + e.what());
        }
      }
      ++n;
    }
    return n;
  }

  void Inject(const std::string& channel, std::vector<uint8_t> data, int64_t utime = 0) {
    pending_.push_back({channel, std::move(data), utime});
  }
  template <typename T>
  void InjectMessage(const std::string& channel, const T& msg, int64_t utime = 0) {
    Inject(channel, EncodeMessage(msg), utime);
  }

  // When true, publications are also delivered to this bus's subscribers (like LCM).
  void set_loopback(bool on) { loopback_ = on; }

  const std::vector<Message>& published() const { return published_; }
  std::vector<Message> PublishedOn(const std::string& channel) const {
    std::vector<Message> out;
    for (const Message& m : published_)
      if (m.channel == channel) out.push_back(m);
    return out;
  }
  // Decodes every message published on `channel` as T; throws if one does not decode.
  template <typename T>
  std::vector<T> Decoded(const std::string& channel) const {
    std::vector<T> out;
    for (const Message& m : published_) {
      if (m.channel != channel) continue;
      T msg{};
      std::string error;
      if (!DecodeMessage(m.data.data(), static_cast<int>(m.data.size()), channel, &msg, &error))
        throw std::runtime_error(error);
      out.push_back(std::move(msg));
    }
    return out;
  }
  void ClearPublished() { published_.clear(); }

 private:
  struct Subscription {
    ChannelMatcher matcher;
    RawHandler handler;
  };
  std::vector<Subscription> subscriptions_;
  std::vector<Message> published_;
  std::deque<Message> pending_;
  bool loopback_ = false;
};

}  // namespace minenav
