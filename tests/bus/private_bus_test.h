#pragma once
// What every test on a real LCM bus shares: it must run inside tests/bus/private_net.sh (a
// private network namespace whose port is in LCM_DEFAULT_URL) and fails loudly otherwise,
// never touching the host network; and a pump that handles messages until a condition holds.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <functional>
#include <string>

#include "common/node/bus.h"

namespace minenav::testing {

class PrivateBusTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const char* in_private_net = std::getenv("MINENAV_IN_PRIVATE_NET");
    ASSERT_TRUE(in_private_net != nullptr && std::string(in_private_net) == "1")
        << "bus tests must run inside tests/bus/private_net.sh (a private network namespace); "
           "register them in CTest as: private_net.sh --port 77NN -- <test binary>";
    const char* url = std::getenv("LCM_DEFAULT_URL");
    ASSERT_TRUE(url != nullptr && url[0] != '\0') << "private_net.sh --port N sets LCM_DEFAULT_URL; it is missing";
    url_ = url;
  }

  // Handles messages on `bus` for `seconds`, or until `done` returns true.
  static bool Pump(Bus& bus, double seconds, const std::function<bool()>& done = nullptr) {
    using Clock = std::chrono::steady_clock;
    const auto end = Clock::now() + std::chrono::duration<double>(seconds);
    while (Clock::now() < end) {
      if (done && done()) return true;
      bus.HandleFor(10'000);
    }
    return done ? done() : true;
  }

  std::string url_;
};

}  // namespace minenav::testing
