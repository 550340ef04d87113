#include "common/node/lcm_bus.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>

#include "common/config.h"
#include "common/log.h"

namespace minenav {

struct LcmBus::Subscription {
  LcmBus* bus = nullptr;
  RawHandler handler;
};

namespace {

// The C callback LCM calls. Nothing may propagate out of it: LCM's dispatch loop is C.
void OnLcmMessage(const lcm::ReceiveBuffer* rbuf, const std::string& channel, void* context) noexcept {
  auto* sub = static_cast<LcmBus::Subscription*>(context);
  try {
    RawMessage raw;
    raw.channel = channel;
    raw.data = static_cast<const uint8_t*>(rbuf->data);
    raw.size = static_cast<int>(rbuf->data_size);
    raw.utime = rbuf->recv_utime;
    sub->handler(raw);
  } catch (const std::exception& e) {
    sub->bus->ReportBad(channel, "channel " + channel + ": handler failed: " + e.what());
  } catch (...) {
    sub->bus->ReportBad(channel, "channel " + channel + ": handler failed with an unknown exception");
  }
}

}  // namespace

LcmBus::LcmBus(const std::string& url, int queue_capacity)
    : url_(url), queue_capacity_(queue_capacity), lcm_(std::make_unique<lcm::LCM>(url)) {
  if (!lcm_->good()) {
    throw std::runtime_error("cannot start LCM on " + url +
                             " (is there a multicast route? see DESIGN.md, \"The bus\")");
  }
}

LcmBus::~LcmBus() = default;

bool LcmBus::Publish(const std::string& channel, const void* data, int size) {
  if (channel.empty() || channel.size() > kMaxChannelNameLength) {
    CountPublished(false, channel);
    return false;
  }
  const bool ok = lcm_->publish(channel, data, static_cast<unsigned int>(size)) == 0;
  CountPublished(ok, channel);
  return ok;
}

void LcmBus::Subscribe(const std::string& channel, RawHandler handler) {
  ValidateChannelPattern(channel);  // an invalid one would crash inside LCM
  auto sub = std::make_unique<Subscription>();
  sub->bus = this;
  sub->handler = std::move(handler);
  lcm::Subscription* s = lcm_->subscribeFunction<void*>(channel, &OnLcmMessage, sub.get());
  if (s == nullptr) throw std::runtime_error("cannot subscribe to channel " + channel);
  if (queue_capacity_ > 0) s->setQueueCapacity(queue_capacity_);
  subscriptions_.push_back(std::move(sub));
}

int LcmBus::HandleFor(int64_t timeout_us) {
  const int timeout_ms = static_cast<int>(std::max<int64_t>(0, (timeout_us + 999) / 1000));
  errno = 0;
  const int status = lcm_->handleTimeout(timeout_ms);
  if (status < 0) {
    if (errno == EINTR) return 0;  // a signal; the caller checks whether to stop
    throw std::runtime_error("LCM receive failed on " + url_ + ": " + std::strerror(errno));
  }
  return status > 0 ? 1 : 0;
}

int LcmBus::fileno() { return lcm_->getFileno(); }

}  // namespace minenav
