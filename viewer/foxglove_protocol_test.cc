#include "viewer/foxglove_protocol.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace minenav::foxglove {
namespace {

using nlohmann::json;

TEST(FoxgloveProtocolTest, MessageDataFrameIsOpcodeSubscriptionTimeAndPayloadLittleEndian) {
  const std::string f = MessageDataFrame(0x01020304u, 0x1112131415161718ull, "{}");
  ASSERT_EQ(f.size(), 15u);
  const std::vector<uint8_t> want = {0x01, 0x04, 0x03, 0x02, 0x01, 0x18, 0x17, 0x16,
                                     0x15, 0x14, 0x13, 0x12, 0x11, '{',  '}'};
  EXPECT_EQ(std::vector<uint8_t>(f.begin(), f.end()), want);
}

TEST(FoxgloveProtocolTest, ServerMessagesFollowTheSpec) {
  const json info = json::parse(ServerInfoJson("bridge", {"clientPublish"}, "42", {{"command_topic", "CMD"}}));
  EXPECT_EQ(info["op"], "serverInfo");
  EXPECT_EQ(info["capabilities"][0], "clientPublish");
  EXPECT_EQ(info["supportedEncodings"][0], "json");
  EXPECT_EQ(info["metadata"]["command_topic"], "CMD");
  EXPECT_FALSE(json::parse(ServerInfoJson("bridge", {}, "42")).contains("supportedEncodings"));
  const json adv = json::parse(AdvertiseJson({{3, "POSE", "json", "minenav.pose_estimate_t", "{}"}}));
  EXPECT_EQ(adv["op"], "advertise");
  EXPECT_EQ(adv["channels"][0]["id"], 3);
  EXPECT_EQ(adv["channels"][0]["topic"], "POSE");
  EXPECT_EQ(adv["channels"][0]["encoding"], "json");
  EXPECT_EQ(adv["channels"][0]["schemaEncoding"], "jsonschema");
  EXPECT_EQ(json::parse(StatusJson(StatusLevel::kError, "no"))["level"], 2);
}

TEST(FoxgloveProtocolTest, ClientOpsParse) {
  const ClientOp s = ParseClientText(R"({"op":"subscribe","subscriptions":[{"id":0,"channelId":3},{"id":1,"channelId":5}]})");
  ASSERT_TRUE(std::holds_alternative<Subscribe>(s));
  EXPECT_EQ(std::get<Subscribe>(s).subscriptions[1].channel_id, 5u);
  EXPECT_EQ(std::get<Unsubscribe>(ParseClientText(R"({"op":"unsubscribe","subscriptionIds":[0]})")).subscription_ids,
            std::vector<uint32_t>{0});
  const ClientOp a = ParseClientText(
      R"({"op":"advertise","channels":[{"id":1,"topic":"CMD","encoding":"json","schemaName":"x"}]})");
  EXPECT_EQ(std::get<ClientAdvertise>(a).channels[0].topic, "CMD");
  const std::string bin = std::string("\x01\x07\x00\x00\x00", 5) + "{\"command\":\"PAUSE\"}";
  const ClientMessageData d = ParseClientBinary(bin);
  EXPECT_EQ(d.channel_id, 7u);
  EXPECT_EQ(d.payload, "{\"command\":\"PAUSE\"}");
}

TEST(FoxgloveProtocolTest, HostileClientMessagesAreOneLineErrors) {
  const std::vector<std::string> hostile = {
      "",
      "not json",
      "[1,2]",
      R"({"nop":"subscribe"})",
      R"({"op":"getParameters","parameterNames":[]})",
      R"({"op":"subscribe"})",
      R"({"op":"subscribe","subscriptions":{}})",
      R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":3}]})",
      R"({"op":"subscribe","subscriptions":[{"id":1.5,"channelId":3}]})",
      R"({"op":"subscribe","subscriptions":[{"id":4294967296,"channelId":3}]})",
      R"({"op":"subscribe","subscriptions":[7]})",
      R"({"op":"unsubscribe","subscriptionIds":["a"]})",
      R"({"op":"advertise","channels":[{"id":1,"topic":5,"encoding":"json","schemaName":"x"}]})",
      R"({"op":"advertise","channels":[{"id":1,"topic":")" + std::string(300, 'T') + R"(","encoding":"json","schemaName":"x"}]})",
      std::string(kMaxClientTextBytes + 1, ' '),
  };
  for (const std::string& text : hostile) {
    try {
      ParseClientText(text);
      ADD_FAILURE() << "accepted: " << text.substr(0, 80);
    } catch (const ProtocolError& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
      EXPECT_LT(std::string(e.what()).size(), 200u) << e.what();
    }
  }
  EXPECT_THROW(ParseClientBinary(""), ProtocolError);
  EXPECT_THROW(ParseClientBinary(std::string("\x01\x00\x00", 3)), ProtocolError);
  EXPECT_THROW(ParseClientBinary(std::string("\x02\x00\x00\x00\x00{}", 7)), ProtocolError);
  EXPECT_THROW(ParseClientBinary(std::string("\x01\x00\x00\x00\x00", 5) + std::string(kMaxClientBinaryBytes, 'x')),
               ProtocolError);
}

TEST(FoxgloveProtocolTest, SessionChecksIdsAgainstWhatTheServerOffers) {
  const auto exists = [](uint32_t id) { return id == 3 || id == 5; };
  ClientSession s;
  s.Apply(ParseClientText(R"({"op":"subscribe","subscriptions":[{"id":10,"channelId":3}]})"), exists);
  EXPECT_EQ(s.SubscriptionFor(3), 10);
  EXPECT_EQ(s.SubscriptionFor(5), -1);
  // An unknown channel, a reused subscription id, a channel subscribed twice.
  EXPECT_THROW(s.Apply(ParseClientText(R"({"op":"subscribe","subscriptions":[{"id":11,"channelId":4}]})"), exists),
               ProtocolError);
  EXPECT_THROW(s.Apply(ParseClientText(R"({"op":"subscribe","subscriptions":[{"id":10,"channelId":5}]})"), exists),
               ProtocolError);
  EXPECT_THROW(s.Apply(ParseClientText(R"({"op":"subscribe","subscriptions":[{"id":12,"channelId":3}]})"), exists),
               ProtocolError);
  s.Apply(ParseClientText(R"({"op":"unsubscribe","subscriptionIds":[10]})"), exists);
  EXPECT_EQ(s.SubscriptionFor(3), -1);
  EXPECT_THROW(s.Apply(ParseClientText(R"({"op":"unsubscribe","subscriptionIds":[10]})"), exists), ProtocolError);
  // No client publishing unless the server offers it, and only on its topics, in JSON.
  const ClientOp adv = ParseClientText(R"({"op":"advertise","channels":[{"id":1,"topic":"CMD","encoding":"json","schemaName":"x"}]})");
  EXPECT_THROW(s.Apply(adv, exists), ProtocolError);
  ClientSession publisher({"CMD"});
  publisher.Apply(adv, exists);
  EXPECT_EQ(publisher.ClientChannelTopic(1), "CMD");
  EXPECT_THROW(publisher.ClientChannelTopic(2), ProtocolError);
  EXPECT_THROW(publisher.Apply(adv, exists), ProtocolError);  // id in use
  EXPECT_THROW(publisher.Apply(ParseClientText(R"({"op":"advertise","channels":[{"id":2,"topic":"DRIVE_COMMAND","encoding":"json","schemaName":"x"}]})"), exists),
               ProtocolError);
  EXPECT_THROW(publisher.Apply(ParseClientText(R"({"op":"advertise","channels":[{"id":2,"topic":"CMD","encoding":"cdr","schemaName":"x"}]})"), exists),
               ProtocolError);
  publisher.Apply(ParseClientText(R"({"op":"unadvertise","channelIds":[1]})"), exists);
  EXPECT_THROW(publisher.ClientChannelTopic(1), ProtocolError);
}

}  // namespace
}  // namespace minenav::foxglove
