#pragma once
// The operator's view's server: HTTP for the page and a WebSocket speaking the Foxglove
// protocol (foxglove_protocol.h), on Boost.Beast, on a thread of its own beside the node's
// loop. The bus stays single-threaded: the node hands display messages over with
// Publish() and collects what clients sent with TakeClientMessages(), both through bounded
// queues, and never waits on a client.
//
// A slow or dead browser never stalls the bridge: each connection has its own queue of
// frames, bounded in bytes; a frame that does not fit is dropped and counted (a dropped
// latched message, the map say, is sent again once the queue has drained). A client that
// sends anything the protocol does not allow gets one status line (level error) and is
// closed (foxglove::ProtocolError).

#include <atomic>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "common/config.h"
#include "viewer/display_stream.h"
#include "viewer/foxglove_protocol.h"

namespace minenav {

struct FoxgloveServerOptions {
  std::string address = "127.0.0.1";  // where to listen: loopback unless asked otherwise
  int port = 8765;                     // 0 = any free port (tests)
  int max_client_queue_kb = 4096;      // KB of frames queued per client before dropping
  int handover_capacity = 1024;        // display messages between the bus thread and the server's
  int max_clients = 16;                // WebSocket connections at once
};
void DeclareOptions(OptionScope scope, FoxgloveServerOptions& o);

// Totals since the start, readable from any thread.
struct FoxgloveServerCounters {
  std::atomic<int64_t> clients_connected{0}, clients_now{0}, clients_dropped{0};
  std::atomic<int64_t> frames_sent{0}, bytes_sent{0};
  std::atomic<int64_t> frames_dropped{0};    // did not fit a slow client's queue
  std::atomic<int64_t> handover_dropped{0};  // did not fit the bus -> server queue
  std::atomic<int64_t> client_messages{0}, client_messages_dropped{0};
};

// A message a client published on one of its channels (an operator command).
struct ClientMessage {
  uint64_t client = 0;
  std::string topic;
  std::string payload;
};

// A file the server serves over HTTP (the page).
struct StaticFile {
  std::string content;
  std::string content_type;
};

// What the bridge node needs of a server: the Foxglove server, or a fake in the node's tests.
class ViewerServer {
 public:
  virtual ~ViewerServer() = default;
  // Any thread: hand over one message (never blocks).
  virtual void Publish(DisplayMessage message) = 0;
  // Any thread: what clients published since the last call.
  virtual std::vector<ClientMessage> TakeClientMessages() = 0;
  // Any thread: a status line to one client; close = drop it after the line is sent.
  virtual void Reply(uint64_t client, foxglove::StatusLevel level, std::string message, bool close) = 0;
  // The counters as a JSON object (clients, bytes_sent, frames_dropped, ...).
  virtual std::string StatsJson() const = 0;
};

class FoxgloveServer final : public ViewerServer {
 public:
  // publish_topics: topics clients may publish on (empty: no clientPublish capability).
  // files: URL path ("/", "/viewer.js") -> file.
  // metadata: serverInfo's (the page reads command_topic and replay_control_topic there).
  FoxgloveServer(FoxgloveServerOptions options, std::string name, std::vector<std::string> publish_topics,
                 std::map<std::string, StaticFile> files, std::map<std::string, std::string> metadata = {});
  ~FoxgloveServer() override;
  FoxgloveServer(const FoxgloveServer&) = delete;
  FoxgloveServer& operator=(const FoxgloveServer&) = delete;

  // Binds and starts the server's thread. Throws std::runtime_error (one line) when the
  // address cannot be bound.
  void Start();
  // Closes every connection and joins the thread. Idempotent.
  void Stop();
  // The port listened on (the one chosen when options.port is 0).
  int port() const { return bound_port_; }

  // Any thread: hand over one message (never blocks; the oldest waiting one is dropped and
  // counted when the queue is full).
  void Publish(DisplayMessage message) override;
  // Any thread: what clients published since the last call (at most 64 wait; more are dropped).
  std::vector<ClientMessage> TakeClientMessages() override;
  // Any thread: a status line to one client; close = drop it after the line is sent.
  void Reply(uint64_t client, foxglove::StatusLevel level, std::string message, bool close) override;
  std::string StatsJson() const override;

  const FoxgloveServerCounters& counters() const { return counters_; }

  struct Impl;  // the Beast side (foxglove_server.cc)

 private:
  friend class Session;
  friend class HttpSession;
  FoxgloveServerOptions options_;
  FoxgloveServerCounters counters_;
  std::unique_ptr<Impl> impl_;
  std::thread thread_;
  int bound_port_ = 0;
  std::atomic<bool> started_{false};

  std::mutex handover_mutex_;
  std::deque<DisplayMessage> handover_;
  bool drain_posted_ = false;

  std::mutex inbound_mutex_;
  std::vector<ClientMessage> inbound_;
};

}  // namespace minenav
