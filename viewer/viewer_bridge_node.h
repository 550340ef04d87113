#pragma once
// viewer_bridge as a node: every message of the bus (channels matching --channels) through
// the DisplayStream (display_stream.h) to the server (foxglove_server.h) that streams it to
// the page and to Foxglove; the fleet table and the bridge's own counters once a period;
// operator commands from the page onto COORDINATOR_COMMAND, only with --allow-commands
// (operator_commands.h). Everything runs on the runtime's loop (the bus stays
// single-threaded); the server's thread is reached only through its bounded queues.

#include <cstdint>
#include <memory>
#include <string>

#include "common/config.h"
#include "common/node/node_runtime.h"
#include "viewer/display_stream.h"
#include "viewer/foxglove_server.h"
#include "viewer/operator_commands.h"

namespace minenav {

struct ViewerBridgeOptions {
  FoxgloveServerOptions server;
  DisplayOptions display;
  std::string channels = ".*";                       // LCM channel pattern shown
  bool allow_commands = false;                       // accept the page's operator commands
  std::string command_channel = "COORDINATOR_COMMAND";
  double fleet_period = 1.0;                         // s between fleet tables
  double command_poll_period = 0.02;                 // s between looks at the clients' commands
};
void DeclareOptions(ConfigSchema& schema, ViewerBridgeOptions& o);

// The bridge's own counters (topic "/minenav/bridge").
inline constexpr const char* kBridgeTopic = "/minenav/bridge";

class ViewerBridgeNode {
 public:
  // `server` outlives the node; authority: issue 16's seam (UnsignedCommandAuthority today).
  ViewerBridgeNode(NodeRuntime& runtime, ViewerBridgeOptions options, ViewerServer& server,
                   std::unique_ptr<CommandAuthority> authority = std::make_unique<UnsignedCommandAuthority>());
  int Run() { return runtime_.Run(); }

  const DisplayStream& stream() const { return stream_; }
  const OperatorCommands& commands() const { return commands_; }

 private:
  void PublishTables(int64_t now);
  void HandleClientMessages(int64_t now);

  NodeRuntime& runtime_;
  ViewerBridgeOptions options_;
  ViewerServer& server_;
  DisplayStream stream_;
  OperatorCommands commands_;
};

}  // namespace minenav
