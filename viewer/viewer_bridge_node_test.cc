#include "viewer/viewer_bridge_node.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "common/node/fake_runtime.h"
#include "minenav/coordinator_command_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/pose_estimate_t.hpp"

namespace minenav {
namespace {

using nlohmann::json;

constexpr int64_t kT0 = 1'700'000'000'000'000;

class FakeViewerServer final : public ViewerServer {
 public:
  void Publish(DisplayMessage m) override { published.push_back(std::move(m)); }
  std::vector<ClientMessage> TakeClientMessages() override { return std::exchange(inbound, {}); }
  void Reply(uint64_t client, foxglove::StatusLevel level, std::string message, bool close) override {
    replies.push_back({client, level, std::move(message), close});
  }
  std::string StatsJson() const override { return R"({"clients":1})"; }

  struct ReplyRecord {
    uint64_t client;
    foxglove::StatusLevel level;
    std::string message;
    bool close;
  };
  std::vector<DisplayMessage> published;
  std::vector<ClientMessage> inbound;
  std::vector<ReplyRecord> replies;

  std::vector<DisplayMessage> On(const std::string& topic) const {
    std::vector<DisplayMessage> out;
    for (const auto& m : published)
      if (m.topic == topic) out.push_back(m);
    return out;
  }
};

struct BridgeFixture {
  explicit BridgeFixture(bool allow_commands) : clock(kT0), fake(clock) {
    ViewerBridgeOptions o;
    o.allow_commands = allow_commands;
    node = std::make_unique<ViewerBridgeNode>(fake.runtime(), o, server);
  }
  ManualClock clock;
  FakeRuntime fake;
  FakeViewerServer server;
  std::unique_ptr<ViewerBridgeNode> node;
};

TEST(ViewerBridgeNodeTest, BusMessagesReachTheServerAndTheFleetTableFollows) {
  BridgeFixture f(false);
  pose_estimate_t p{};
  p.utime = kT0;
  p.source = "clue";
  p.pose.x = 4.0;
  f.fake.bus().InjectMessage("POSE", p, kT0);
  heartbeat_t h{};
  h.utime = kT0;
  h.process = "contour_mapper";
  h.state = heartbeat_t::OK;
  f.fake.bus().InjectMessage("HEARTBEAT", h, kT0);
  f.fake.runtime().SpinOnce(0);
  f.clock.Advance(1'000'000);
  f.fake.runtime().SpinOnce(0);

  ASSERT_EQ(f.server.On("POSE").size(), 1u);
  EXPECT_EQ(json::parse(f.server.On("POSE")[0].payload)["pose"]["x"], 4.0);
  ASSERT_FALSE(f.server.On(kFleetTopic).empty());
  EXPECT_EQ(json::parse(f.server.On(kFleetTopic).back().payload)["processes"][0]["process"], "contour_mapper");
  EXPECT_EQ(f.server.On(kViewerConfigTopic).size(), 1u);
  const json bridge = json::parse(f.server.On(kBridgeTopic).back().payload);
  EXPECT_EQ(bridge["commands_allowed"], false);
  EXPECT_EQ(bridge["server"]["clients"], 1);
}

TEST(ViewerBridgeNodeTest, ABadMessageIsCountedNotShown) {
  BridgeFixture f(false);
  f.fake.bus().Inject("POSE", {1, 2, 3}, kT0);
  f.fake.runtime().SpinOnce(0);
  EXPECT_TRUE(f.server.On("POSE").empty());
  EXPECT_EQ(f.fake.bus().counters().messages_bad, 1);
}

TEST(ViewerBridgeNodeTest, CommandsReachTheBusOnlyWithTheFlag) {
  BridgeFixture allowed(true);
  allowed.server.inbound.push_back({7, "COORDINATOR_COMMAND", R"({"command":"PAUSE"})"});
  allowed.fake.runtime().SpinOnce(0);
  const auto sent = allowed.fake.bus().Decoded<coordinator_command_t>("COORDINATOR_COMMAND");
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].command, coordinator_command_t::PAUSE);
  EXPECT_EQ(sent[0].seq, 1);
  EXPECT_EQ(sent[0].utime, kT0);
  ASSERT_EQ(allowed.server.replies.size(), 1u);
  EXPECT_FALSE(allowed.server.replies[0].close);
  EXPECT_EQ(allowed.server.replies[0].client, 7u);

  // A hostile payload: refused, the client dropped, nothing on the bus.
  allowed.server.inbound.push_back({8, "COORDINATOR_COMMAND", R"({"command":"LOAD_MISSION"})"});
  allowed.clock.Advance(100'000);
  allowed.fake.runtime().SpinOnce(0);
  EXPECT_EQ(allowed.fake.bus().PublishedOn("COORDINATOR_COMMAND").size(), 1u);
  EXPECT_TRUE(allowed.server.replies.back().close);

  BridgeFixture refused(false);
  refused.server.inbound.push_back({7, "COORDINATOR_COMMAND", R"({"command":"ESTOP"})"});
  refused.fake.runtime().SpinOnce(0);
  EXPECT_TRUE(refused.fake.bus().PublishedOn("COORDINATOR_COMMAND").empty());
  ASSERT_EQ(refused.server.replies.size(), 1u);
  EXPECT_EQ(refused.server.replies[0].level, foxglove::StatusLevel::kError);
}

}  // namespace
}  // namespace minenav

namespace minenav {
namespace {

TEST(ViewerBridgeNodeTest, ReplayPlaysOnSeeksAndObeysOnlyValidControls) {
  std::vector<LogEvent> events;
  for (int k = 0; k < 10; ++k) {  // a pose a second, x = k
    pose_estimate_t p{};
    p.utime = kT0 + k * 1'000'000;
    p.source = "clue";
    p.pose.x = k;
    LogEvent e;
    e.channel = "POSE";
    e.timestamp = p.utime;
    e.data = EncodeMessage(p);
    events.push_back(std::move(e));
  }
  const LogReplay replay(std::move(events));
  ManualClock clock(5'000'000);
  FakeRuntime fake(clock);
  FakeViewerServer server;
  ViewerBridgeOptions o;
  o.replay_speed = 2.0;
  o.allow_commands = true;
  ViewerBridgeNode node(fake.runtime(), o, server, &replay);
  const auto last_x = [&] { return json::parse(server.On("POSE").back().payload)["pose"]["x"].get<double>(); };
  ASSERT_EQ(server.On("POSE").size(), 1u);  // the state at the start: the first pose
  EXPECT_EQ(last_x(), 0.0);
  for (int i = 0; i < 20; ++i) {  // 1 s of clock at speed 2: the log plays to 2 s
    fake.runtime().SpinOnce(0);
    clock.Advance(50'000);
  }
  fake.runtime().SpinOnce(0);
  EXPECT_EQ(last_x(), 2.0);
  EXPECT_EQ(json::parse(server.On(kReplayTopic).back().payload)["generation"], 1);

  server.published.clear();
  server.inbound.push_back({3, kReplayControlTopic, R"({"seek_s":6.5,"paused":true})"});
  clock.Advance(50'000);  // the commands' timer is due
  fake.runtime().SpinOnce(0);
  ASSERT_FALSE(server.On(kReplayTopic).empty());
  const json status = json::parse(server.On(kReplayTopic).front().payload);
  EXPECT_EQ(status["generation"], 2);
  EXPECT_DOUBLE_EQ(status["time_s"].get<double>(), 6.5);
  // Every pose up to 6.5 s for the track, after the new generation.
  ASSERT_EQ(server.On("POSE").size(), 7u);
  EXPECT_EQ(server.published.front().topic, kReplayTopic);
  EXPECT_EQ(last_x(), 6.0);
  server.published.clear();
  clock.Advance(1'000'000);
  fake.runtime().SpinOnce(0);
  EXPECT_TRUE(server.On("POSE").empty());  // paused

  for (const std::string bad : {R"({"seek_s":99})", R"({"speed":0})", R"({"rm":"-rf"})", R"("x")"}) {
    server.inbound.push_back({4, kReplayControlTopic, bad});
    clock.Advance(50'000);
    fake.runtime().SpinOnce(0);
    ASSERT_FALSE(server.replies.empty());
    EXPECT_TRUE(server.replies.back().close) << bad;
  }
  // No operator commands in a replay, even with the flag.
  server.inbound.push_back({5, "COORDINATOR_COMMAND", R"({"command":"PAUSE"})"});
  clock.Advance(50'000);
  fake.runtime().SpinOnce(0);
  EXPECT_TRUE(fake.bus().PublishedOn("COORDINATOR_COMMAND").empty());
}

}  // namespace
}  // namespace minenav
