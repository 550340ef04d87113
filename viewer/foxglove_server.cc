#include "viewer/foxglove_server.h"

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include <chrono>
#include <set>
#include <stdexcept>
#include <utility>

#include "common/log.h"

namespace minenav {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = boost::beast::http;
namespace websocket = boost::beast::websocket;
using tcp = boost::asio::ip::tcp;

void DeclareOptions(OptionScope s, FoxgloveServerOptions& o) {
  s.AddString("address", &o.address,
              "address to listen on: 127.0.0.1 (this machine only); another address opens the view, "
              "and with --allow-commands the vehicle's commands, to that network");
  s.AddInt("port", &o.port, "TCP port of the page and the WebSocket (0 = any free port)", 0, 65535);
  s.AddInt("max_client_queue_kb", &o.max_client_queue_kb,
           "KB of frames queued for one browser before new ones are dropped (a slow client)", 64, 1 << 20);
  s.AddInt("handover_capacity", &o.handover_capacity,
           "display messages waiting between the bus thread and the server thread before the oldest is dropped", 8,
           100000);
  s.AddInt("max_clients", &o.max_clients, "WebSocket connections at once", 1, 256);
}

namespace {

constexpr size_t kMaxInbound = 64;

struct Channel {
  foxglove::ServerChannel info;
  bool latched = false;
  std::shared_ptr<const DisplayMessage> latest;  // latched channels: the newest message
};

}  // namespace

class Session;

struct FoxgloveServer::Impl {
  Impl(FoxgloveServer& s, std::string n, std::vector<std::string> topics, std::map<std::string, StaticFile> f)
      : server(s), name(std::move(n)), publish_topics(std::move(topics)), files(std::move(f)), acceptor(ioc) {}

  void Accept();
  void Drain();
  void Handle(const DisplayMessage& m);
  Channel* ChannelById(uint32_t id) {
    const auto it = channels_by_id.find(id);
    return it == channels_by_id.end() ? nullptr : &channels[it->second];
  }
  std::vector<foxglove::ServerChannel> AllChannels() const {
    std::vector<foxglove::ServerChannel> all;
    for (const auto& [topic, c] : channels) all.push_back(c.info);
    return all;
  }
  std::vector<std::shared_ptr<Session>> LiveSessions();

  FoxgloveServer& server;
  std::string name;
  std::vector<std::string> publish_topics;
  std::map<std::string, StaticFile> files;
  std::string session_id;
  std::map<std::string, std::string> metadata;
  asio::io_context ioc;
  tcp::acceptor acceptor;
  std::map<std::string, Channel> channels;  // by topic
  std::map<uint32_t, std::string> channels_by_id;
  uint32_t next_channel_id = 1;
  uint64_t next_client = 1;
  std::map<uint64_t, std::weak_ptr<Session>> sessions;
};

// One WebSocket client. Lives on the server thread only.
class Session : public std::enable_shared_from_this<Session> {
 public:
  Session(FoxgloveServer::Impl& impl, tcp::socket socket, uint64_t id, bool may_publish)
      : impl_(impl),
        ws_(std::move(socket)),
        id_(id),
        may_publish_(may_publish && !impl.publish_topics.empty()),
        state_(may_publish_ ? impl.publish_topics : std::vector<std::string>{}) {
    beast::error_code ec;
    const tcp::endpoint peer = ws_.next_layer().socket().remote_endpoint(ec);
    peer_ = ec ? "?" : peer.address().to_string() + ":" + std::to_string(peer.port());
  }

  uint64_t id() const { return id_; }

  void Run(http::request<http::empty_body> request) {
    ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws_.set_option(websocket::stream_base::decorator([](websocket::response_type& res) {
      res.set(http::field::sec_websocket_protocol, foxglove::kSubprotocol);
      res.set(http::field::server, "minenav viewer_bridge");
    }));
    // Beast closes on anything larger without a word (close code 1009); up to this size the
    // protocol's own limits answer with a status line first.
    ws_.read_message_max(1 << 20);
    ws_.async_accept(request, [self = shared_from_this()](beast::error_code ec) { self->OnAccept(ec); });
  }

  // A frame for this client; dropped (and counted) when its queue is full.
  void Enqueue(std::shared_ptr<const std::string> frame, bool binary, uint32_t latched_channel = 0) {
    if (closing_) return;
    const size_t limit = static_cast<size_t>(impl_.server.options_.max_client_queue_kb) * 1024;
    if (queued_bytes_ + frame->size() > limit && !queue_.empty()) {
      ++impl_.server.counters_.frames_dropped;
      if (latched_channel != 0) stale_.insert(latched_channel);
      return;
    }
    queued_bytes_ += frame->size();
    queue_.push_back({std::move(frame), binary});
    if (!writing_) Write();
  }

  void SendText(const std::string& text) { Enqueue(std::make_shared<const std::string>(text), false); }

  // The message on a channel this client subscribed to (no-op otherwise).
  void Deliver(const Channel& channel, const DisplayMessage& m) {
    const int64_t sub = state_.SubscriptionFor(channel.info.id);
    if (sub < 0) return;
    const uint64_t ns = m.utime > 0 ? static_cast<uint64_t>(m.utime) * 1000u : 0u;
    Enqueue(std::make_shared<const std::string>(foxglove::MessageDataFrame(static_cast<uint32_t>(sub), ns, m.payload)),
            true, channel.latched ? channel.info.id : 0);
  }

  // One status line, then the connection closes.
  void Fail(const std::string& why) {
    if (closing_) return;
    MINENAV_LOG(kWarn) << "client " << id_ << " (" << peer_ << ") dropped: " << why;
    ++impl_.server.counters_.clients_dropped;
    // What waits is not sent: the error goes out next, then the close.
    while (queue_.size() > (writing_ ? 1u : 0u)) {
      queued_bytes_ -= queue_.back().frame->size();
      queue_.pop_back();
    }
    SendText(foxglove::StatusJson(foxglove::StatusLevel::kError, why));
    closing_ = true;
  }

 private:
  struct Queued {
    std::shared_ptr<const std::string> frame;
    bool binary = false;
  };

  void OnAccept(beast::error_code ec) {
    if (ec) return;
    ++impl_.server.counters_.clients_connected;
    ++impl_.server.counters_.clients_now;
    counted_ = true;
    std::vector<std::string> capabilities;
    if (may_publish_) capabilities.push_back("clientPublish");
    SendText(foxglove::ServerInfoJson(impl_.name, capabilities, impl_.session_id, impl_.metadata));
    SendText(foxglove::AdvertiseJson(impl_.AllChannels()));
    Read();
  }

  void Read() {
    ws_.async_read(buffer_, [self = shared_from_this()](beast::error_code ec, size_t) { self->OnRead(ec); });
  }

  void OnRead(beast::error_code ec) {
    if (ec) {
      return;
    }
    const std::string data = beast::buffers_to_string(buffer_.data());
    buffer_.consume(buffer_.size());
    try {
      if (ws_.got_text()) {
        const foxglove::ClientOp op = foxglove::ParseClientText(data);
        state_.Apply(op, [this](uint32_t id) { return impl_.ChannelById(id) != nullptr; });
        if (const auto* s = std::get_if<foxglove::Subscribe>(&op)) {
          for (const auto& item : s->subscriptions) {
            const Channel* c = impl_.ChannelById(item.channel_id);
            if (c && c->latest) Deliver(*c, *c->latest);
          }
        }
      } else {
        const foxglove::ClientMessageData d = foxglove::ParseClientBinary(data);
        const std::string& topic = state_.ClientChannelTopic(d.channel_id);
        FoxgloveServer& server = impl_.server;
        std::lock_guard<std::mutex> lock(server.inbound_mutex_);
        if (server.inbound_.size() >= kMaxInbound) {
          ++server.counters_.client_messages_dropped;
        } else {
          server.inbound_.push_back({id_, topic, std::string(d.payload)});
          ++server.counters_.client_messages;
        }
      }
    } catch (const foxglove::ProtocolError& e) {
      Fail(e.what());
      return;
    }
    if (!closing_) Read();
  }

  void Write() {
    writing_ = true;
    const Queued& q = queue_.front();
    ws_.binary(q.binary);
    ws_.async_write(asio::buffer(*q.frame),
                    [self = shared_from_this()](beast::error_code ec, size_t n) { self->OnWrite(ec, n); });
  }

  void OnWrite(beast::error_code ec, size_t bytes) {
    writing_ = false;
    if (ec) {
      queue_.clear();
      queued_bytes_ = 0;
      return;
    }
    ++impl_.server.counters_.frames_sent;
    impl_.server.counters_.bytes_sent += static_cast<int64_t>(bytes);
    queued_bytes_ -= queue_.front().frame->size();
    queue_.pop_front();
    if (queue_.empty() && !stale_.empty() && !closing_) {
      // Latched messages dropped while the client was slow: their newest now.
      const std::set<uint32_t> stale = std::move(stale_);
      stale_.clear();
      for (const uint32_t id : stale) {
        const Channel* c = impl_.ChannelById(id);
        if (c && c->latest) Deliver(*c, *c->latest);
      }
    }
    if (!queue_.empty()) {
      Write();
    } else if (closing_) {
      ws_.async_close(websocket::close_code::policy_error, [self = shared_from_this()](beast::error_code) {});
    }
  }

 public:
  ~Session() {
    if (counted_) --impl_.server.counters_.clients_now;
  }

 private:
  FoxgloveServer::Impl& impl_;
  websocket::stream<beast::tcp_stream> ws_;
  beast::flat_buffer buffer_;
  uint64_t id_;
  bool may_publish_;
  std::string peer_;
  foxglove::ClientSession state_;
  std::deque<Queued> queue_;
  size_t queued_bytes_ = 0;
  bool writing_ = false;
  bool closing_ = false;
  bool counted_ = false;
  std::set<uint32_t> stale_;
};

// One HTTP request: the page's files, or the upgrade to a WebSocket.
class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(FoxgloveServer::Impl& impl, tcp::socket socket) : impl_(impl), stream_(std::move(socket)) {}

  void Run() {
    parser_.header_limit(8 * 1024);
    parser_.body_limit(0);
    stream_.expires_after(std::chrono::seconds(10));
    http::async_read(stream_, buffer_, parser_,
                     [self = shared_from_this()](beast::error_code ec, size_t) { self->OnRead(ec); });
  }

 private:
  void OnRead(beast::error_code ec) {
    if (ec) return;
    http::request<http::empty_body> req = parser_.release();
    if (websocket::is_upgrade(req)) {
      Upgrade(std::move(req));
      return;
    }
    if (req.method() != http::verb::get && req.method() != http::verb::head) {
      Respond(req, http::status::method_not_allowed, "only GET and HEAD\n", "text/plain");
      return;
    }
    std::string target(req.target());
    if (const size_t q = target.find('?'); q != std::string::npos) target.resize(q);
    const auto it = impl_.files.find(target == "/" ? "/index.html" : target);
    if (it == impl_.files.end()) {
      Respond(req, http::status::not_found, "not found\n", "text/plain");
      return;
    }
    Respond(req, http::status::ok, it->second.content, it->second.content_type);
  }

  void Upgrade(http::request<http::empty_body> req) {
    const std::string protocols(req[http::field::sec_websocket_protocol]);
    if (protocols.find(foxglove::kSubprotocol) == std::string::npos) {
      Respond(req, http::status::bad_request, std::string("WebSocket subprotocol must be ") + foxglove::kSubprotocol + "\n",
              "text/plain");
      return;
    }
    if (impl_.server.counters_.clients_now >= impl_.server.options_.max_clients) {
      Respond(req, http::status::service_unavailable, "too many clients\n", "text/plain");
      return;
    }
    // Commands only from a page this server served (or a client that sends no Origin, as
    // Foxglove's desktop app): a web page elsewhere may show the view, never move the vehicle.
    const std::string origin(req[http::field::origin]);
    const std::string host(req[http::field::host]);
    const bool may_publish = origin.empty() || origin == "http://" + host;
    stream_.expires_never();
    auto session = std::make_shared<Session>(impl_, stream_.release_socket(), impl_.next_client++, may_publish);
    impl_.sessions[session->id()] = session;
    session->Run(std::move(req));
  }

  void Respond(const http::request<http::empty_body>& req, http::status status, const std::string& body,
               const std::string& type) {
    auto res = std::make_shared<http::response<http::string_body>>(status, req.version());
    res->set(http::field::server, "minenav viewer_bridge");
    res->set(http::field::content_type, type);
    res->set(http::field::cache_control, "no-store");
    res->keep_alive(false);
    if (req.method() != http::verb::head) res->body() = body;
    res->prepare_payload();
    if (req.method() == http::verb::head) res->content_length(body.size());
    http::async_write(stream_, *res, [self = shared_from_this(), res](beast::error_code, size_t) {
      beast::error_code ec;
      self->stream_.socket().shutdown(tcp::socket::shutdown_send, ec);
    });
  }

  FoxgloveServer::Impl& impl_;
  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  http::request_parser<http::empty_body> parser_;
};

std::vector<std::shared_ptr<Session>> FoxgloveServer::Impl::LiveSessions() {
  std::vector<std::shared_ptr<Session>> live;
  for (auto it = sessions.begin(); it != sessions.end();) {
    if (auto s = it->second.lock()) {
      live.push_back(std::move(s));
      ++it;
    } else {
      it = sessions.erase(it);
    }
  }
  return live;
}

void FoxgloveServer::Impl::Accept() {
  acceptor.async_accept(ioc, [this](beast::error_code ec, tcp::socket socket) {
    if (ec) {
      if (ec == asio::error::operation_aborted) return;
    } else {
      std::make_shared<HttpSession>(*this, std::move(socket))->Run();
    }
    Accept();
  });
}

void FoxgloveServer::Impl::Drain() {
  std::deque<DisplayMessage> batch;
  {
    std::lock_guard<std::mutex> lock(server.handover_mutex_);
    batch.swap(server.handover_);
    server.drain_posted_ = false;
  }
  for (const DisplayMessage& m : batch) Handle(m);
}

void FoxgloveServer::Impl::Handle(const DisplayMessage& m) {
  auto it = channels.find(m.topic);
  const std::vector<std::shared_ptr<Session>> live = LiveSessions();
  if (it == channels.end()) {
    Channel c;
    c.info.id = next_channel_id++;
    c.info.topic = m.topic;
    c.info.schema_name = m.schema_name;
    c.info.schema = m.schema;
    c.latched = m.latched;
    it = channels.emplace(m.topic, std::move(c)).first;
    channels_by_id[it->second.info.id] = m.topic;
    const std::string advertise = foxglove::AdvertiseJson({it->second.info});
    for (const auto& s : live) s->SendText(advertise);
  }
  Channel& c = it->second;
  auto shared = std::make_shared<const DisplayMessage>(m);
  if (c.latched) c.latest = shared;
  for (const auto& s : live) s->Deliver(c, *shared);
}

std::string FoxgloveServer::StatsJson() const {
  const FoxgloveServerCounters& c = counters_;
  return "{\"clients\":" + std::to_string(c.clients_now.load()) +
         ",\"clients_connected\":" + std::to_string(c.clients_connected.load()) +
         ",\"clients_dropped\":" + std::to_string(c.clients_dropped.load()) +
         ",\"frames_sent\":" + std::to_string(c.frames_sent.load()) +
         ",\"bytes_sent\":" + std::to_string(c.bytes_sent.load()) +
         ",\"frames_dropped\":" + std::to_string(c.frames_dropped.load()) +
         ",\"handover_dropped\":" + std::to_string(c.handover_dropped.load()) + "}";
}

FoxgloveServer::FoxgloveServer(FoxgloveServerOptions options, std::string name, std::vector<std::string> publish_topics,
                               std::map<std::string, StaticFile> files, std::map<std::string, std::string> metadata)
    : options_(std::move(options)),
      impl_(std::make_unique<Impl>(*this, std::move(name), std::move(publish_topics), std::move(files))) {
  impl_->metadata = std::move(metadata);
  impl_->session_id = std::to_string(std::chrono::system_clock::now().time_since_epoch().count());
}

FoxgloveServer::~FoxgloveServer() { Stop(); }

void FoxgloveServer::Start() {
  beast::error_code ec;
  const asio::ip::address address = asio::ip::make_address(options_.address, ec);
  if (ec) throw UsageError("--address " + options_.address + ": not an IP address");
  const tcp::endpoint endpoint(address, static_cast<unsigned short>(options_.port));
  tcp::acceptor& acceptor = impl_->acceptor;
  acceptor.open(endpoint.protocol(), ec);
  if (!ec) acceptor.set_option(asio::socket_base::reuse_address(true), ec);
  if (!ec) acceptor.bind(endpoint, ec);
  if (!ec) acceptor.listen(asio::socket_base::max_listen_connections, ec);
  if (ec)
    throw std::runtime_error("cannot listen on " + options_.address + ":" + std::to_string(options_.port) + ": " +
                             ec.message());
  bound_port_ = acceptor.local_endpoint().port();
  impl_->Accept();
  started_ = true;
  thread_ = std::thread([this] { impl_->ioc.run(); });
}

void FoxgloveServer::Stop() {
  if (!started_) return;
  started_ = false;
  // The sessions' pending operations (and so the sessions) end with the io_context.
  impl_->ioc.stop();
  if (thread_.joinable()) thread_.join();
}

void FoxgloveServer::Publish(DisplayMessage message) {
  std::lock_guard<std::mutex> lock(handover_mutex_);
  if (handover_.size() >= static_cast<size_t>(options_.handover_capacity)) {
    handover_.pop_front();
    ++counters_.handover_dropped;
  }
  handover_.push_back(std::move(message));
  if (!drain_posted_ && started_) {
    drain_posted_ = true;
    asio::post(impl_->ioc, [this] { impl_->Drain(); });
  }
}

std::vector<ClientMessage> FoxgloveServer::TakeClientMessages() {
  std::lock_guard<std::mutex> lock(inbound_mutex_);
  std::vector<ClientMessage> out;
  out.swap(inbound_);
  return out;
}

void FoxgloveServer::Reply(uint64_t client, foxglove::StatusLevel level, std::string message, bool close) {
  if (!started_) return;
  asio::post(impl_->ioc, [this, client, level, message = std::move(message), close] {
    const auto it = impl_->sessions.find(client);
    if (it == impl_->sessions.end()) return;
    const std::shared_ptr<Session> s = it->second.lock();
    if (!s) return;
    if (close) {
      s->Fail(message);
    } else {
      s->SendText(foxglove::StatusJson(level, message));
    }
  });
}

}  // namespace minenav
