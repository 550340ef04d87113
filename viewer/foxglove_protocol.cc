#include "viewer/foxglove_protocol.h"

#include <algorithm>

#include <nlohmann/json.hpp>

namespace minenav::foxglove {
namespace {

using nlohmann::json;

std::string Dump(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }

const json& Field(const json& j, const char* name, const char* op) {
  const auto it = j.find(name);
  if (it == j.end()) throw ProtocolError(std::string(op) + ": missing \"" + name + "\"");
  return *it;
}

uint32_t Id(const json& j, const char* name, const char* op) {
  const json& v = Field(j, name, op);
  if (!v.is_number_integer() || v.get<int64_t>() < 0 || v.get<int64_t>() > int64_t{UINT32_MAX})
    throw ProtocolError(std::string(op) + ": \"" + name + "\" is not an unsigned 32-bit integer");
  return static_cast<uint32_t>(v.get<int64_t>());
}

std::string Text(const json& j, const char* name, const char* op) {
  const json& v = Field(j, name, op);
  if (!v.is_string()) throw ProtocolError(std::string(op) + ": \"" + name + "\" is not a string");
  std::string s = v.get<std::string>();
  if (s.size() > kMaxTopicBytes) throw ProtocolError(std::string(op) + ": \"" + name + "\" is too long");
  return s;
}

const json& Array(const json& j, const char* name, const char* op, size_t max) {
  const json& v = Field(j, name, op);
  if (!v.is_array()) throw ProtocolError(std::string(op) + ": \"" + name + "\" is not an array");
  if (v.size() > max) throw ProtocolError(std::string(op) + ": more than " + std::to_string(max) + " " + name);
  return v;
}

std::vector<uint32_t> Ids(const json& j, const char* name, const char* op, size_t max) {
  std::vector<uint32_t> ids;
  for (const json& v : Array(j, name, op, max)) {
    if (!v.is_number_integer() || v.get<int64_t>() < 0 || v.get<int64_t>() > int64_t{UINT32_MAX})
      throw ProtocolError(std::string(op) + ": an id in \"" + name + "\" is not an unsigned 32-bit integer");
    ids.push_back(static_cast<uint32_t>(v.get<int64_t>()));
  }
  return ids;
}

void PutLittleEndian(std::string& out, uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}

}  // namespace

std::string ServerInfoJson(const std::string& name, const std::vector<std::string>& capabilities,
                           const std::string& session_id, const std::map<std::string, std::string>& metadata) {
  json j = {{"op", "serverInfo"}, {"name", name}, {"capabilities", capabilities}, {"sessionId", session_id},
            {"metadata", metadata}};
  if (std::find(capabilities.begin(), capabilities.end(), "clientPublish") != capabilities.end())
    j["supportedEncodings"] = {"json"};
  return Dump(j);
}

std::string StatusJson(StatusLevel level, const std::string& message) {
  return Dump({{"op", "status"}, {"level", static_cast<int>(level)}, {"message", message}});
}

std::string AdvertiseJson(const std::vector<ServerChannel>& channels) {
  json list = json::array();
  for (const ServerChannel& c : channels)
    list.push_back({{"id", c.id},
                    {"topic", c.topic},
                    {"encoding", c.encoding},
                    {"schemaName", c.schema_name},
                    {"schema", c.schema},
                    {"schemaEncoding", "jsonschema"}});
  return Dump({{"op", "advertise"}, {"channels", std::move(list)}});
}

std::string UnadvertiseJson(const std::vector<uint32_t>& channel_ids) {
  return Dump({{"op", "unadvertise"}, {"channelIds", channel_ids}});
}

std::string MessageDataFrame(uint32_t subscription_id, uint64_t timestamp_ns, std::string_view payload) {
  std::string frame;
  frame.reserve(13 + payload.size());
  frame.push_back(0x01);
  PutLittleEndian(frame, subscription_id, 4);
  PutLittleEndian(frame, timestamp_ns, 8);
  frame.append(payload);
  return frame;
}

ClientOp ParseClientText(std::string_view text) {
  if (text.size() > kMaxClientTextBytes)
    throw ProtocolError("text message of " + std::to_string(text.size()) + " bytes (at most " +
                        std::to_string(kMaxClientTextBytes) + ")");
  json j = json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw ProtocolError("text message is not a JSON object");
  const auto op_it = j.find("op");
  if (op_it == j.end() || !op_it->is_string()) throw ProtocolError("text message has no string \"op\"");
  const std::string op = op_it->get<std::string>();
  if (op == "subscribe") {
    Subscribe s;
    for (const json& item : Array(j, "subscriptions", "subscribe", kMaxSubscriptions)) {
      if (!item.is_object()) throw ProtocolError("subscribe: a subscription is not an object");
      s.subscriptions.push_back({Id(item, "id", "subscribe"), Id(item, "channelId", "subscribe")});
    }
    return s;
  }
  if (op == "unsubscribe") return Unsubscribe{Ids(j, "subscriptionIds", "unsubscribe", kMaxSubscriptions)};
  if (op == "advertise") {
    ClientAdvertise a;
    for (const json& c : Array(j, "channels", "advertise", kMaxClientChannels)) {
      if (!c.is_object()) throw ProtocolError("advertise: a channel is not an object");
      a.channels.push_back({Id(c, "id", "advertise"), Text(c, "topic", "advertise"), Text(c, "encoding", "advertise"),
                            Text(c, "schemaName", "advertise")});
    }
    return a;
  }
  if (op == "unadvertise") return ClientUnadvertise{Ids(j, "channelIds", "unadvertise", kMaxClientChannels)};
  std::string shown = op.substr(0, 40);
  throw ProtocolError("unsupported op \"" + shown + "\"");
}

ClientMessageData ParseClientBinary(std::string_view frame) {
  if (frame.size() > kMaxClientBinaryBytes)
    throw ProtocolError("binary message of " + std::to_string(frame.size()) + " bytes (at most " +
                        std::to_string(kMaxClientBinaryBytes) + ")");
  if (frame.size() < 5) throw ProtocolError("binary message of " + std::to_string(frame.size()) + " bytes is too short");
  const auto byte = [&](size_t i) { return static_cast<uint32_t>(static_cast<uint8_t>(frame[i])); };
  if (byte(0) != 0x01) throw ProtocolError("binary opcode " + std::to_string(byte(0)) + " is not client message data (1)");
  ClientMessageData d;
  d.channel_id = byte(1) | (byte(2) << 8) | (byte(3) << 16) | (byte(4) << 24);
  d.payload = frame.substr(5);
  return d;
}

int64_t ClientSession::SubscriptionFor(uint32_t channel_id) const {
  const auto it = by_channel_.find(channel_id);
  return it == by_channel_.end() ? -1 : int64_t{it->second};
}

const std::string& ClientSession::ClientChannelTopic(uint32_t client_channel_id) const {
  const auto it = client_channels_.find(client_channel_id);
  if (it == client_channels_.end())
    throw ProtocolError("message data on client channel " + std::to_string(client_channel_id) +
                        ", which was never advertised");
  return it->second.topic;
}

void ClientSession::AddSubscription(const Subscribe::Item& item) {
  if (subscriptions_.count(item.id)) throw ProtocolError("subscribe: subscription id " + std::to_string(item.id) + " is in use");
  if (by_channel_.count(item.channel_id))
    throw ProtocolError("subscribe: channel " + std::to_string(item.channel_id) + " is already subscribed");
  if (subscriptions_.size() >= kMaxSubscriptions) throw ProtocolError("subscribe: too many subscriptions");
  subscriptions_[item.id] = item.channel_id;
  by_channel_[item.channel_id] = item.id;
}

void ClientSession::ApplyOther(const ClientOp& op) {
  if (const auto* u = std::get_if<Unsubscribe>(&op)) {
    for (const uint32_t id : u->subscription_ids) {
      const auto it = subscriptions_.find(id);
      if (it == subscriptions_.end()) throw ProtocolError("unsubscribe: no subscription " + std::to_string(id));
      by_channel_.erase(it->second);
      subscriptions_.erase(it);
    }
  } else if (const auto* a = std::get_if<ClientAdvertise>(&op)) {
    if (accepted_publish_topics_.empty()) throw ProtocolError("advertise: this server does not accept client messages");
    for (const ClientAdvertise::Channel& c : a->channels) {
      if (std::find(accepted_publish_topics_.begin(), accepted_publish_topics_.end(), c.topic) ==
          accepted_publish_topics_.end())
        throw ProtocolError("advertise: topic \"" + c.topic + "\" does not accept client messages");
      if (c.encoding != "json") throw ProtocolError("advertise: encoding \"" + c.encoding + "\" (only json)");
      if (client_channels_.count(c.id)) throw ProtocolError("advertise: client channel " + std::to_string(c.id) + " is in use");
      if (client_channels_.size() >= kMaxClientChannels) throw ProtocolError("advertise: too many client channels");
      client_channels_[c.id] = c;
    }
  } else if (const auto* ua = std::get_if<ClientUnadvertise>(&op)) {
    for (const uint32_t id : ua->channel_ids) {
      if (!client_channels_.erase(id)) throw ProtocolError("unadvertise: no client channel " + std::to_string(id));
    }
  }
}

}  // namespace minenav::foxglove
