// The server on a real socket (127.0.0.1, a free port): the page over HTTP, the Foxglove
// handshake, subscriptions, latched messages, client commands, hostile clients, and a client
// that never reads (the bridge must not stall).
#include "viewer/foxglove_server.h"

#include <gtest/gtest.h>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include <chrono>
#include <nlohmann/json.hpp>
#include <atomic>
#include <thread>

namespace minenav {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = boost::beast::http;
namespace websocket = boost::beast::websocket;
using tcp = boost::asio::ip::tcp;
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

// A blocking Foxglove client with a read timeout.
class Client {
 public:
  explicit Client(int port, const std::string& origin = "") : ws_(ioc_) {
    tcp::resolver resolver(ioc_);
    beast::get_lowest_layer(ws_).connect(*resolver.resolve("127.0.0.1", std::to_string(port)).begin());
    ws_.set_option(websocket::stream_base::decorator([origin](websocket::request_type& req) {
      req.set(http::field::sec_websocket_protocol, "foxglove.websocket.v1");
      if (!origin.empty()) req.set(http::field::origin, origin);
    }));
    websocket::response_type res;
    ws_.handshake(res, "127.0.0.1:" + std::to_string(port), "/");
    protocol_ = std::string(res[http::field::sec_websocket_protocol]);
  }
  const std::string& protocol() const { return protocol_; }

  // The next frame: text (JSON) or binary; "" on close or after 5 s.
  std::string Next(bool* binary = nullptr) {
    beast::get_lowest_layer(ws_).expires_after(std::chrono::seconds(5));
    beast::flat_buffer b;
    beast::error_code ec;
    ws_.read(b, ec);
    if (ec) {
      error_ = ec;
      return "";
    }
    if (binary) *binary = ws_.got_binary();
    return beast::buffers_to_string(b.data());
  }
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
  void SendText(const std::string& s) {
    ws_.text(true);
    ws_.write(asio::buffer(s));
  }
  void SendBinary(const std::string& s) {
    ws_.binary(true);
    ws_.write(asio::buffer(s));
  }
  beast::error_code error() const { return error_; }

 private:
  asio::io_context ioc_;
  websocket::stream<beast::tcp_stream> ws_;
  std::string protocol_;
  beast::error_code error_;
};

// The channel id of `topic` in an advertise.
int64_t ChannelId(const json& advertise, const std::string& topic) {
  for (const json& c : advertise["channels"])
    if (c["topic"] == topic) return c["id"];
  return -1;
}

TEST(FoxgloveServerTest, ServesThePageOverHttp) {
  auto server = StartServer();
  asio::io_context ioc;
  beast::tcp_stream stream(ioc);
  tcp::resolver resolver(ioc);
  stream.connect(*resolver.resolve("127.0.0.1", std::to_string(server->port())).begin());
  http::request<http::empty_body> req(http::verb::get, "/", 11);
  req.set(http::field::host, "127.0.0.1");
  http::write(stream, req);
  beast::flat_buffer b;
  http::response<http::string_body> res;
  http::read(stream, b, res);
  EXPECT_EQ(res.result(), http::status::ok);
  EXPECT_EQ(res.body(), "<html>page</html>");
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
    EXPECT_TRUE(c.error() == websocket::error::closed || c.error() == asio::error::eof ||
                c.error() == asio::error::connection_reset)
        << c.error().message();
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
