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
#include "viewer/log_replay.h"
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
  std::string replay;                                // a log to show with a time slider instead of the bus
  double replay_speed = 1.0;                         // log seconds per second at the start
  std::string net_namespace;                         // join it for the bus after the port is open (a demo's)
};
void DeclareOptions(ConfigSchema& schema, ViewerBridgeOptions& o);

// The bridge's own counters (topic "/minenav/bridge").
inline constexpr const char* kBridgeTopic = "/minenav/bridge";
// Replay (--replay LOG): where the replay is (topic) and how the page moves it (client topic:
// {"seek_s": s from the log's start, "speed": x, "paused": bool}, any of them).
inline constexpr const char* kReplayTopic = "/minenav/replay";
inline constexpr const char* kReplayControlTopic = "/minenav/replay_control";

class ViewerBridgeNode {
 public:
  // `server` outlives the node; authority: issue 16's seam (UnsignedCommandAuthority today).
  // replay: the log of --replay (null: the live bus); it outlives the node.
  ViewerBridgeNode(NodeRuntime& runtime, ViewerBridgeOptions options, ViewerServer& server,
                   const LogReplay* replay = nullptr,
                   std::unique_ptr<CommandAuthority> authority = std::make_unique<UnsignedCommandAuthority>());
  int Run() { return runtime_.Run(); }

  const DisplayStream& stream() const { return stream_; }
  const OperatorCommands& commands() const { return commands_; }

 private:
  void PublishTables(int64_t now);
  void HandleClientMessages(int64_t now);
  void Show(std::string_view channel, const uint8_t* data, size_t size, int64_t utime);
  // Replay: plays on to the clock's time, seeks, obeys the page's controls.
  void ReplayTick(int64_t now);
  void ReplaySeek(int64_t log_utime);
  std::string ReplayControl(const std::string& payload);  // "" or why it is refused
  void PublishReplayStatus();

  NodeRuntime& runtime_;
  ViewerBridgeOptions options_;
  ViewerServer& server_;
  DisplayStream stream_;
  OperatorCommands commands_;
  const LogReplay* replay_;
  int64_t replay_time_ = 0;       // us, log time shown
  int64_t replay_wall_ = -1;      // us, clock time of the last tick
  int64_t replay_generation_ = 0; // seeks so far: the page starts afresh on a new one
  int64_t replay_status_sent_ = 0;
  double replay_speed_ = 1.0;
  bool replay_paused_ = false;
};

}  // namespace minenav
