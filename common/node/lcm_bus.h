#pragma once
// The live bus: LCM over UDP multicast (DESIGN.md, "The bus").

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/node/bus.h"

namespace lcm {
class LCM;
}

namespace minenav {

class LcmBus final : public Bus {
 public:
  // `url` as given by ResolveLcmUrl(). `queue_capacity`: messages each subscription may
  // hold before LCM drops the oldest (LCM's default of 30 is too few for a burst of scans
  // behind a slow handler). Throws std::runtime_error when LCM cannot start on `url`.
  explicit LcmBus(const std::string& url, int queue_capacity = 1000);
  ~LcmBus() override;

  bool Publish(const std::string& channel, const void* data, int size) override;
  void Subscribe(const std::string& channel, RawHandler handler) override;
  // Waits up to timeout_us for one message and dispatches it. Returns 1 if a message
  // was handled, 0 on timeout or when a signal interrupted the wait; throws on failure.
  int HandleFor(int64_t timeout_us) override;

  const std::string& url() const { return url_; }
  // The file descriptor LCM reads from, for select()/poll() by tools.
  int fileno();

  struct Subscription;  // one handler; LCM calls it through a C callback

 private:
  std::string url_;
  int queue_capacity_;
  std::unique_ptr<lcm::LCM> lcm_;
  std::vector<std::unique_ptr<Subscription>> subscriptions_;
};

}  // namespace minenav
