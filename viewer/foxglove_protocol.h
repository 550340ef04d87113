#pragma once
// The Foxglove WebSocket protocol (subprotocol foxglove.websocket.v1; spec:
// github.com/foxglove/ws-protocol docs/spec.md), the part the operator's view speaks, as
// plain functions and one per-connection state: no sockets, so every rule is unit-tested.
//
// Server -> client: serverInfo, status, advertise, unadvertise (JSON text); Message Data
// (binary: opcode 0x01, uint32 subscription id, uint64 receive time in ns, payload; little
// endian). Client -> server: subscribe, unsubscribe, and with the clientPublish capability
// advertise / unadvertise of client channels (JSON text) and Client Message Data (binary:
// opcode 0x01, uint32 channel id, payload). Everything else from a client (other ops,
// malformed JSON, unknown ids, absurd sizes) is a ProtocolError: the server answers it with
// one status line and closes the connection.

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace minenav::foxglove {

inline constexpr const char* kSubprotocol = "foxglove.websocket.v1";

// Limits on what one client may ask for (more is hostile, not a use).
inline constexpr size_t kMaxClientTextBytes = 64 * 1024;
inline constexpr size_t kMaxClientBinaryBytes = 16 * 1024;
inline constexpr size_t kMaxSubscriptions = 1024;
inline constexpr size_t kMaxClientChannels = 16;
inline constexpr size_t kMaxTopicBytes = 256;

class ProtocolError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ServerChannel {
  uint32_t id = 0;
  std::string topic, encoding = "json", schema_name, schema;
};

enum class StatusLevel { kInfo = 0, kWarning = 1, kError = 2 };

std::string ServerInfoJson(const std::string& name, const std::vector<std::string>& capabilities,
                           const std::string& session_id, const std::map<std::string, std::string>& metadata = {});
std::string StatusJson(StatusLevel level, const std::string& message);
std::string AdvertiseJson(const std::vector<ServerChannel>& channels);
std::string UnadvertiseJson(const std::vector<uint32_t>& channel_ids);
// The binary Message Data frame.
std::string MessageDataFrame(uint32_t subscription_id, uint64_t timestamp_ns, std::string_view payload);

// What a client may send.
struct Subscribe {
  struct Item {
    uint32_t id = 0, channel_id = 0;
  };
  std::vector<Item> subscriptions;
};
struct Unsubscribe {
  std::vector<uint32_t> subscription_ids;
};
struct ClientAdvertise {
  struct Channel {
    uint32_t id = 0;
    std::string topic, encoding, schema_name;
  };
  std::vector<Channel> channels;
};
struct ClientUnadvertise {
  std::vector<uint32_t> channel_ids;
};
using ClientOp = std::variant<Subscribe, Unsubscribe, ClientAdvertise, ClientUnadvertise>;

// Parses a client's text frame. Throws ProtocolError (one line) for anything else.
ClientOp ParseClientText(std::string_view text);

struct ClientMessageData {
  uint32_t channel_id = 0;
  std::string_view payload;  // points into the frame
};
// Parses a client's binary frame. Throws ProtocolError.
ClientMessageData ParseClientBinary(std::string_view frame);

// One connection's subscriptions and client channels, checked against what the server
// offers. Apply() throws ProtocolError for an id the server never advertised, a reused
// subscription id, a second subscription of one channel, too many of anything, or client
// publishing when the server did not offer it (or on a topic it does not accept).
class ClientSession {
 public:
  // accepted_publish_topics: the topics a client may publish on (empty = no clientPublish).
  explicit ClientSession(std::vector<std::string> accepted_publish_topics = {})
      : accepted_publish_topics_(std::move(accepted_publish_topics)) {}

  // `channel_exists(id)` tells whether the server advertised channel id.
  template <typename ChannelExists>
  void Apply(const ClientOp& op, ChannelExists channel_exists) {
    if (const auto* s = std::get_if<Subscribe>(&op)) {
      for (const Subscribe::Item& item : s->subscriptions) {
        if (!channel_exists(item.channel_id))
          throw ProtocolError("subscribe: no channel " + std::to_string(item.channel_id));
        AddSubscription(item);
      }
    } else {
      ApplyOther(op);
    }
  }

  // The subscription id of `channel_id`, or -1 when the client has none.
  int64_t SubscriptionFor(uint32_t channel_id) const;
  // The topic of a client channel; throws ProtocolError for an id it never advertised.
  const std::string& ClientChannelTopic(uint32_t client_channel_id) const;
  size_t subscription_count() const { return subscriptions_.size(); }

 private:
  void AddSubscription(const Subscribe::Item& item);
  void ApplyOther(const ClientOp& op);

  std::vector<std::string> accepted_publish_topics_;
  std::map<uint32_t, uint32_t> subscriptions_;  // subscription id -> channel id
  std::map<uint32_t, uint32_t> by_channel_;     // channel id -> subscription id
  std::map<uint32_t, ClientAdvertise::Channel> client_channels_;
};

}  // namespace minenav::foxglove
