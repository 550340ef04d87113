#include "viewer/viewer_bridge_node.h"

#include <utility>

#include "common/file_io.h"
#include "common/log.h"
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
}

ViewerBridgeNode::ViewerBridgeNode(NodeRuntime& runtime, ViewerBridgeOptions options, ViewerServer& server,
                                   std::unique_ptr<CommandAuthority> authority)
    : runtime_(runtime),
      options_(std::move(options)),
      server_(server),
      stream_(options_.display),
      commands_(options_.allow_commands, std::move(authority)) {
  ValidateChannelPattern(options_.channels);
  Bus& bus = runtime_.bus();
  bus.Subscribe(options_.channels, [this, &bus](const RawMessage& raw) {
    try {
      std::optional<DisplayMessage> d = stream_.OnMessage(raw.channel, raw.data, static_cast<size_t>(raw.size), raw.utime);
      if (d) server_.Publish(std::move(*d));
      bus.CountHandled();
    } catch (const std::exception& e) {
      bus.ReportBad(raw.channel, e.what());
    }
  });
  server_.Publish(stream_.ViewerConfig());
  runtime_.AddTimer(options_.fleet_period, [this](int64_t now) { PublishTables(now); });
  runtime_.AddTimer(options_.command_poll_period, [this](int64_t now) { HandleClientMessages(now); });
}

void ViewerBridgeNode::PublishTables(int64_t now) {
  server_.Publish(stream_.FleetTable(now));
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
