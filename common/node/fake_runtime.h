#pragma once
// A NodeRuntime on a FakeBus and a clock the test owns: what the unit test of a node runs
// on (no network, no threads; timers fire when the test advances the clock and spins).
//
//   ManualClock clock(kT0);
//   FakeRuntime fake(clock);  // no heartbeats unless a period is given
//   MyNode node(fake.runtime(), options);
//   fake.bus().InjectMessage("ODOMETRY", msg);
//   clock.Advance(100'000);
//   fake.runtime().SpinOnce(0);  // due timers, then the injected messages

#include <memory>
#include <string>

#include "common/clock.h"
#include "common/node/fake_bus.h"
#include "common/node/node_runtime.h"

namespace minenav {

class FakeRuntime {
 public:
  explicit FakeRuntime(Clock& clock, double heartbeat_period = 0.0, const std::string& process = "test_node") {
    NodeOptions options;
    options.heartbeat_period = heartbeat_period;
    runtime_ = std::make_unique<NodeRuntime>(process, options);
    auto bus = std::make_unique<FakeBus>();
    bus_ = bus.get();
    runtime_->StartWith(std::move(bus), clock);
  }

  NodeRuntime& runtime() { return *runtime_; }
  FakeBus& bus() { return *bus_; }

 private:
  std::unique_ptr<NodeRuntime> runtime_;
  FakeBus* bus_ = nullptr;  // owned by the runtime
};

}  // namespace minenav
