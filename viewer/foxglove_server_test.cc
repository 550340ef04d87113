// The server on a real socket (127.0.0.1, a free port): the page over HTTP, the Foxglove
// handshake, subscriptions, latched messages, client commands, hostile clients, and a client
// that never reads (the bridge must not stall).
#include "viewer/foxglove_server.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <nlohmann/json.hpp>
#include <thread>

#include "viewer/testing/websocket_test_client.h"

namespace minenav {
namespace {

using nlohmann::json;

DisplayMessage Message(const std::string& topic, const std::string& payload, bool latched = false) {
  DisplayMessage m;
  m.topic = topic;
  m.schema_name = "test." + topic;
  m.schema = R"({"type":"object"})";
  m.payload = payload;
  m.utime = 1'000'000;
  m.latched = latched;
  return m;
}

std::unique_ptr<FoxgloveServer> StartServer(std::vector<std::string> publish_topics = {}, int queue_kb = 4096) {
  std::map<std::string, std::string> metadata;
  if (!publish_topics.empty()) metadata["command_topic"] = publish_topics.front();
  FoxgloveServerOptions o;
  o.port = 0;
  o.max_client_queue_kb = queue_kb;
  auto s = std::make_unique<FoxgloveServer>(o, "test", std::move(publish_topics),
                                            std::map<std::string, StaticFile>{{"/index.html", {"<html>page</html>", "text/html"}}}, metadata);
  s->Start();
  return s;
}

// The Foxglove client of the tests: JSON frames on the raw WebSocket client.
class Client : public testing::WebSocketTestClient {
 public:
  explicit Client(int port, const std::string& origin = "")
      : WebSocketTestClient(port, "foxglove.websocket.v1", origin) {}
  json NextJson() {
    bool binary = true;
    const std::string s = Next(&binary);
    EXPECT_FALSE(binary);
    return s.empty() ? json() : json::parse(s);
  }
  // Reads until a JSON op `op`; returns it.
  json NextOp(const std::string& op) {
    for (int i = 0; i < 50; ++i) {
      bool binary = false;
      const std::string s = Next(&binary);
      if (s.empty()) return json();
      if (!binary && json::parse(s)["op"] == op) return json::parse(s);
    }
    return json();
  }
};

// The channel id of `topic` in an advertise.
int64_t ChannelId(const json& advertise, const std::string& topic) {
  for (const json& c : advertise["channels"])
    if (c["topic"] == topic) return c["id"];
  return -1;
}

TEST(FoxgloveServerTest, ServesThePageOverHttp) {
  auto server = StartServer();
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<uint16_t>(server->port()));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(connect(fd, reinterpret_cast<const sockaddr*>(&a), sizeof(a)), 0);
  const std::string req = "GET / HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n";
  ASSERT_EQ(send(fd, req.data(), req.size(), 0), static_cast<ssize_t>(req.size()));
  std::string res;
  char buf[4096];
  for (ssize_t n; (n = recv(fd, buf, sizeof(buf), 0)) > 0;) res.append(buf, static_cast<size_t>(n));
  close(fd);
  EXPECT_EQ(res.rfind("HTTP/1.1 200", 0), 0u) << res.substr(0, 80);
  EXPECT_EQ(res.substr(res.find("\r\n\r\n") + 4), "<html>page</html>");
}

TEST(FoxgloveServerTest, HandshakeAdvertiseSubscribeAndLatchedMessages) {
  auto server = StartServer();
  server->Publish(Message("MAP", R"({"version":1})", true));
  server->Publish(Message("POSE", R"({"x":1})"));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));

  Client c(server->port());
  EXPECT_EQ(c.protocol(), "foxglove.websocket.v1");
  const json info = c.NextJson();
  EXPECT_EQ(info["op"], "serverInfo");
  EXPECT_TRUE(info["capabilities"].empty());  // no clientPublish without publish topics
  const json adv = c.NextJson();
  ASSERT_EQ(adv["op"], "advertise");
  const int64_t map = ChannelId(adv, "MAP"), pose = ChannelId(adv, "POSE");
  ASSERT_GT(map, 0);
  ASSERT_GT(pose, 0);
  EXPECT_EQ(adv["channels"][0]["encoding"], "json");

  c.SendText(json({{"op", "subscribe"}, {"subscriptions", {{{"id", 5}, {"channelId", map}}, {{"id", 6}, {"channelId", pose}}}}}).dump());
  // The latched map arrives at once; the pose stream only with the next pose.
  bool binary = false;
  std::string f = c.Next(&binary);
  ASSERT_TRUE(binary);
  ASSERT_GE(f.size(), 13u);
  EXPECT_EQ(f[0], 1);
  EXPECT_EQ(f[1], 5);  // subscription id 5
  EXPECT_EQ(f.substr(13), R"({"version":1})");
  server->Publish(Message("POSE", R"({"x":2})"));
  f = c.Next(&binary);
  EXPECT_EQ(f[1], 6);
  EXPECT_EQ(f.substr(13), R"({"x":2})");
  // A new topic is advertised to connected clients.
  server->Publish(Message("NEW", "{}"));
  EXPECT_GT(ChannelId(c.NextOp("advertise"), "NEW"), 0);
}

TEST(FoxgloveServerTest, ClientCommandsAreHandedOverOnlyOnAcceptedTopics) {
  auto server = StartServer({"COORDINATOR_COMMAND"});
  Client c(server->port());
  const json info = c.NextJson();
  EXPECT_EQ(info["capabilities"][0], "clientPublish");
  EXPECT_EQ(info["metadata"]["command_topic"], "COORDINATOR_COMMAND");
  c.SendText(R"({"op":"advertise","channels":[{"id":2,"topic":"COORDINATOR_COMMAND","encoding":"json","schemaName":"x"}]})");
  c.SendBinary(std::string("\x01\x02\x00\x00\x00", 5) + R"({"command":"PAUSE"})");
  std::vector<ClientMessage> got;
  for (int i = 0; i < 100 && got.empty(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    got = server->TakeClientMessages();
  }
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].topic, "COORDINATOR_COMMAND");
  EXPECT_EQ(got[0].payload, R"({"command":"PAUSE"})");
  server->Reply(got[0].client, foxglove::StatusLevel::kInfo, "sent", false);
  EXPECT_EQ(c.NextOp("status")["message"], "sent");

  // A page served elsewhere (another Origin) may watch but not command.
  Client foreign(server->port(), "http://evil.example");
  EXPECT_TRUE(foreign.NextJson()["capabilities"].empty());
}

TEST(FoxgloveServerTest, HostileClientsGetOneErrorLineAndAreDropped) {
  auto server = StartServer();
  const std::vector<std::pair<std::string, bool>> hostile = {
      {"not json", false},
      {R"({"op":"getParameters"})", false},
      {R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":999}]})", false},
      {R"({"op":"advertise","channels":[{"id":2,"topic":"COORDINATOR_COMMAND","encoding":"json","schemaName":"x"}]})", false},
      {std::string("\x01\x02\x00\x00\x00{}", 7), true},
      {std::string(100 * 1024, 'x'), false},
  };
  for (const auto& [payload, binary] : hostile) {
    Client c(server->port());
    c.NextJson();
    c.NextJson();
    binary ? c.SendBinary(payload) : c.SendText(payload);
    const json status = c.NextOp("status");
    EXPECT_EQ(status["level"], 2) << payload.substr(0, 60);
    EXPECT_EQ(status["message"].get<std::string>().find('\n'), std::string::npos);
    EXPECT_EQ(c.Next(), "");  // then closed
    EXPECT_TRUE(c.closed());
  }
  EXPECT_GE(server->counters().clients_dropped.load(), static_cast<int64_t>(hostile.size()) - 1);
}

TEST(FoxgloveServerTest, AClientThatNeverReadsNeitherStallsPublishNorOtherClients) {
  auto server = StartServer({}, /*queue_kb=*/1024);
  server->Publish(Message("SCAN", "{}"));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  Client stuck(server->port());  // subscribes, then never reads again
  stuck.NextJson();
  const int64_t scan = ChannelId(stuck.NextJson(), "SCAN");
  stuck.SendText(json({{"op", "subscribe"}, {"subscriptions", {{{"id", 1}, {"channelId", scan}}}}}).dump());
  Client healthy(server->port());
  healthy.NextJson();
  healthy.NextJson();
  healthy.SendText(json({{"op", "subscribe"}, {"subscriptions", {{{"id", 1}, {"channelId", scan}}}}}).dump());
  std::this_thread::sleep_for(std::chrono::milliseconds(100));

  constexpr int kMessages = 1000;  // 20 kB each: 20 MB for each client in about 2 s
  std::atomic<int> received{0};
  std::thread reader([&] {
    while (received < kMessages && !healthy.Next().empty()) ++received;
  });
  const std::string payload = "\"" + std::string(20000, 'x') + "\"";
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < kMessages; ++i) {
    server->Publish(Message("SCAN", payload));
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  reader.join();
  EXPECT_LT(seconds, 10.0);  // Publish never waited for the stuck client
  EXPECT_GE(received.load(), kMessages * 99 / 100);
  EXPECT_GT(server->counters().frames_dropped.load(), 100);  // the stuck client's, counted
  EXPECT_EQ(server->counters().handover_dropped.load(), 0);
}

}  // namespace
}  // namespace minenav
