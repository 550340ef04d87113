#include "viewer/viewer_bridge_node.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <nlohmann/json.hpp>

#include "common/file_io.h"
#include "common/log.h"
#include "common/message_auth.h"
#include "common/node/bus.h"
#include "minenav/heartbeat_t.hpp"

namespace minenav {

namespace {

constexpr const char* kBridgeSchema = R"js({"type":"object","title":"minenav.viewer.bridge",)js"
    R"js("description":"the bridge's counters since it started: WebSocket clients now and in all, frames and bytes sent, frames dropped for slow clients, messages dropped between the bus and the server, commands accepted and refused",)js"
    R"js("properties":{"utime":{"type":"integer"},"commands_allowed":{"type":"boolean"},"server":{"type":"object"},)js"
    R"js("commands_accepted":{"type":"integer"},"commands_refused":{"type":"integer"},"throttled":{"type":"integer"}},"required":["utime"]})js";

}  // namespace

void DeclareOptions(ConfigSchema& schema, ViewerBridgeOptions& o) {
  OptionScope s(schema);
  DeclareOptions(s, o.server);
  DeclareOptions(s.Nested("display"), o.display);
  s.AddString("channels", &o.channels, "LCM channel pattern (regular expression) of what the view may show");
  s.AddBool("allow_commands", &o.allow_commands,
            "accept the page's operator commands (start, pause, resume, abort, e-stop) and publish them on "
            "command_channel; without it every command is refused");
  schema.AddChannel("command_channel", &o.command_channel, "publishes", "coordinator_command_t",
                    "the operator's commands to the coordinator (only with --allow-commands)");
  s.AddDouble("fleet_period", &o.fleet_period, "s", "period of the fleet table (heartbeats) and the bridge's counters",
              0.1, 60.0);
  s.AddDouble("command_poll_period", &o.command_poll_period, "s", "period of the look at the clients' commands",
              0.001, 1.0);
  s.AddString("replay", &o.replay,
              "show this LCM log with a time slider instead of the bus (loaded into memory; commands are refused)");
  s.AddDouble("replay_speed", &o.replay_speed, "", "log seconds played per second at the start", 0.01, 100.0);
  s.AddString("net_namespace", &o.net_namespace,
              "network namespace of the bus, e.g. /proc/PID/ns/net of a process of the demo: the page's port opens "
              "here, then the bridge joins that namespace for LCM (needs root; viewer/view_demo.sh)");
}

ViewerBridgeNode::ViewerBridgeNode(NodeRuntime& runtime, ViewerBridgeOptions options, ViewerServer& server,
                                   const LogReplay* replay, std::unique_ptr<CommandAuthority> authority)
    : runtime_(runtime),
      options_(std::move(options)),
      server_(server),
      stream_(options_.display),
      commands_(options_.allow_commands && replay == nullptr, std::move(authority)),
      replay_(replay),
      replay_speed_(options_.replay_speed) {
  ValidateChannelPattern(options_.channels);
  server_.Publish(stream_.ViewerConfig());
  if (replay_) {
    ReplaySeek(replay_->start_utime());
    runtime_.AddTimer(0.05, [this](int64_t now) { ReplayTick(now); });
  } else {
    Bus& bus = runtime_.bus();
    bus.Subscribe(options_.channels, [this, &bus](const RawMessage& raw) {
      try {
        Show(raw.channel, raw.data, static_cast<size_t>(raw.size), raw.utime);
        bus.CountHandled();
      } catch (const std::exception& e) {
        bus.ReportBad(raw.channel, e.what());
      }
    });
  }
  runtime_.AddTimer(options_.fleet_period, [this](int64_t now) { PublishTables(now); });
  runtime_.AddTimer(options_.command_poll_period, [this](int64_t now) { HandleClientMessages(now); });
}

void ViewerBridgeNode::Show(std::string_view channel, const uint8_t* data, size_t size, int64_t utime) {
  // A signed command read from a log, or live without --auth.key-file, still carries its
  // authentication trailer (common/message_auth.h): shown without it.
  size = static_cast<size_t>(StripAuthTrailer(data, static_cast<int>(size)));
  for (DisplayMessage& d : stream_.OnMessageWithFoxglove(channel, data, size, utime)) server_.Publish(std::move(d));
}

void ViewerBridgeNode::PublishTables(int64_t now) {
  server_.Publish(stream_.FleetTable(replay_ ? replay_time_ : now));
  DisplayMessage b;
  b.topic = kBridgeTopic;
  b.schema_name = "minenav.viewer.bridge";
  b.schema = kBridgeSchema;
  b.utime = now;
  b.payload = "{\"utime\":" + std::to_string(now) + ",\"commands_allowed\":" + (commands_.allowed() ? "true" : "false") +
              ",\"server\":" + server_.StatsJson() + ",\"commands_accepted\":" + std::to_string(commands_.accepted()) +
              ",\"commands_refused\":" + std::to_string(commands_.refused()) +
              ",\"throttled\":" + std::to_string(stream_.counters().throttled) + "}";
  b.latched = true;
  server_.Publish(std::move(b));
}

void ViewerBridgeNode::HandleClientMessages(int64_t now) {
  for (const ClientMessage& m : server_.TakeClientMessages()) {
    if (replay_ && m.topic == kReplayControlTopic) {
      if (std::string why = ReplayControl(m.payload); !why.empty())
        server_.Reply(m.client, foxglove::StatusLevel::kError, why, true);
      continue;
    }
    if (m.topic != options_.command_channel) {
      server_.Reply(m.client, foxglove::StatusLevel::kError, "topic " + m.topic + " takes no messages", true);
      continue;
    }
    const OperatorCommandResult r = commands_.Accept(m.payload, now);
    if (!r.command) {
      MINENAV_LOG(kWarn) << "operator command from client " << m.client << " refused: " << r.error;
      server_.Reply(m.client, foxglove::StatusLevel::kError, r.error, true);
      continue;
    }
    Publish(runtime_.bus(), options_.command_channel, *r.command);
    MINENAV_LOG(kInfo) << "operator command " << static_cast<int>(r.command->command) << " (seq " << r.command->seq
                       << ") from client " << m.client << " published on " << options_.command_channel;
    server_.Reply(m.client, foxglove::StatusLevel::kInfo,
                  "command sent on " + options_.command_channel + " (seq " + std::to_string(r.command->seq) + ")",
                  false);
  }
}

}  // namespace minenav

namespace minenav {

void ViewerBridgeNode::ReplaySeek(int64_t log_utime) {
  replay_time_ = std::clamp(log_utime, replay_->start_utime(), replay_->end_utime());
  ++replay_generation_;
  // The page starts afresh when it sees the new generation; then the state at that moment.
  stream_ = DisplayStream(options_.display);
  PublishReplayStatus();
  for (const size_t i : replay_->Seek(replay_time_)) {
    const LogEvent& e = replay_->event(i);
    try {
      Show(e.channel, e.data.data(), e.data.size(), e.timestamp);
    } catch (const std::exception& ex) {
      MINENAV_LOG(kDebug) << "replay: " << ex.what();
    }
  }
}

void ViewerBridgeNode::ReplayTick(int64_t now) {
  const int64_t dt = replay_wall_ < 0 ? 0 : now - replay_wall_;
  replay_wall_ = now;
  if (!replay_paused_ && dt > 0) {
    const int64_t next = std::min(replay_->end_utime(), replay_time_ + static_cast<int64_t>(static_cast<double>(dt) * replay_speed_));
    for (const size_t i : replay_->Between(replay_time_, next)) {
      const LogEvent& e = replay_->event(i);
      try {
        Show(e.channel, e.data.data(), e.data.size(), e.timestamp);
      } catch (const std::exception& ex) {
        MINENAV_LOG(kDebug) << "replay: " << ex.what();
      }
    }
    replay_time_ = next;
    if (replay_time_ >= replay_->end_utime()) replay_paused_ = true;
  }
  if (now - replay_status_sent_ >= 200'000) {
    replay_status_sent_ = now;
    PublishReplayStatus();
  }
}

void ViewerBridgeNode::PublishReplayStatus() {
  DisplayMessage m;
  m.topic = kReplayTopic;
  m.schema_name = "minenav.viewer.replay";
  m.schema = R"js({"type":"object","title":"minenav.viewer.replay","description":"where the replay of a log is: time from the log's start and its length (s), speed, paused; a new generation follows each seek (the page starts afresh)","properties":{"generation":{"type":"integer"},"time_s":{"type":"number"},"duration_s":{"type":"number"},"speed":{"type":"number"},"paused":{"type":"boolean"},"log_utime":{"type":"integer"}}})js";
  const nlohmann::json j = {{"generation", replay_generation_},
                            {"time_s", static_cast<double>(replay_time_ - replay_->start_utime()) * 1e-6},
                            {"duration_s", static_cast<double>(replay_->end_utime() - replay_->start_utime()) * 1e-6},
                            {"speed", replay_speed_},
                            {"paused", replay_paused_},
                            {"log_utime", replay_time_}};
  m.payload = j.dump();
  m.utime = replay_time_;
  m.latched = true;
  server_.Publish(std::move(m));
}

std::string ViewerBridgeNode::ReplayControl(const std::string& payload) {
  if (payload.size() > 1024) return "replay control of " + std::to_string(payload.size()) + " bytes (at most 1024)";
  const nlohmann::json j = nlohmann::json::parse(payload, nullptr, false);
  if (j.is_discarded() || !j.is_object() || j.empty()) return "replay control is not a JSON object";
  for (const auto& [key, value] : j.items()) {
    if (key == "seek_s" || key == "speed") {
      if (!value.is_number() || !std::isfinite(value.get<double>())) return "replay control: " + key + " is not a number";
    } else if (key == "paused") {
      if (!value.is_boolean()) return "replay control: paused is not true/false";
    } else {
      return "replay control: unknown key \"" + key.substr(0, 20) + "\" (seek_s, speed, paused)";
    }
  }
  if (j.contains("speed")) {
    const double speed = j["speed"];
    if (speed < 0.01 || speed > 100.0) return "replay control: speed outside [0.01, 100]";
    replay_speed_ = speed;
  }
  if (j.contains("paused")) replay_paused_ = j["paused"].get<bool>();
  if (j.contains("seek_s")) {
    const double s = j["seek_s"];
    const double duration = static_cast<double>(replay_->end_utime() - replay_->start_utime()) * 1e-6;
    if (s < 0.0 || s > duration + 1e-6) return "replay control: seek_s outside the log [0, " + std::to_string(duration) + "] s";
    ReplaySeek(replay_->start_utime() + static_cast<int64_t>(s * 1e6));
  } else {
    PublishReplayStatus();
  }
  return "";
}

}  // namespace minenav
