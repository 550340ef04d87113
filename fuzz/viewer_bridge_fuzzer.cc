// Fuzz target: viewer_bridge's handlers (viewer/viewer_bridge_node.h) with hostile messages on
// every channel of the fleet (the bridge subscribes them all and decodes each by its channel's
// type) and hostile operator commands from the page (allow_commands: the last pseudo-channel's
// payload is what a WebSocket client published on COORDINATOR_COMMAND) (fuzz/node_fuzz.h).
// Every display message must be valid JSON (the page parses it) and every command the bridge
// puts on the bus must be one the coordinator accepts.

#include <nlohmann/json.hpp>

#include "fuzz/node_fuzz.h"
#include "viewer/viewer_bridge_node.h"

namespace {

using namespace minenav;

// The server's side of the node: display messages checked, client messages handed in.
class FuzzServer final : public ViewerServer {
 public:
  void Publish(DisplayMessage message) override {
    if (!nlohmann::json::accept(message.payload))
      fuzz::Fail("display message on " + message.topic + " is not JSON: " + message.payload.substr(0, 200));
  }
  std::vector<ClientMessage> TakeClientMessages() override { return std::exchange(from_clients_, {}); }
  void Reply(uint64_t, foxglove::StatusLevel, std::string, bool) override {}
  std::string StatsJson() const override { return "{}"; }
  void FromClient(std::string payload) { from_clients_.push_back({1, "COORDINATOR_COMMAND", std::move(payload)}); }

 private:
  std::vector<ClientMessage> from_clients_;
};

const std::vector<std::string> kChannels = {
    "LADAR_SCAN",  "ODOMETRY",    "POSE",         "CONTOUR_MAP", "LINE_MAP",       "SIM_WORLD",
    "SIM_TRUTH",   "PATH",        "DRIVE_PATH",   "PATH_REQUEST", "DRIVE_COMMAND", "TASK_STATUS",
    "TASK_PLAN",   "TASK_REQUEST", "MISSION_STATUS", "CUTTER_STATE", "CUT_TASK",    "HEARTBEAT",
    "COORDINATOR_COMMAND", "UNKNOWN_CHANNEL"};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto h = fuzz::NodeFuzzHarness::Live("viewer_bridge");
  h->ExpectOutput<coordinator_command_t>("COORDINATOR_COMMAND");
  FuzzServer server;
  ViewerBridgeOptions options;
  options.allow_commands = true;
  ViewerBridgeNode node(h->runtime(), options, server);
  h->Spin();
  for (const fuzz::FuzzMessage& m : fuzz::ParseNodeFuzzInput(data, size, kChannels.size() + 1)) {
    h->clock().Advance(m.delay_us);
    if (m.channel == kChannels.size()) {
      server.FromClient(std::string(reinterpret_cast<const char*>(m.data), m.size));
    } else {
      h->bus().Inject(kChannels[m.channel], std::vector<uint8_t>(m.data, m.data + m.size), h->clock().NowUtime());
    }
    h->Spin();
  }
  for (int i = 0; i < 20; ++i) {
    h->clock().Advance(100'000);
    h->Spin();
  }
  return 0;
}
