// viewer_bridge: the operator's view. Serves a page (http://127.0.0.1:8765/ by default) that
// draws the mine, the vehicle and the mission as they happen, and streams the bus over a
// WebSocket in the Foxglove protocol (Foxglove or Lichtblick connect to the same address).
// viewer/README.md; the node is viewer/viewer_bridge_node.h.

#include <fcntl.h>
#include <sched.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/log.h"
#include "common/node/node_runtime.h"
#include "viewer/viewer_bridge_node.h"
#include "viewer/viewer_page_text.h"

namespace {

// The calling thread (the one that will make the LCM socket) joins the network namespace at
// `path`; sockets made before (the page's) stay where they were made.
void JoinNetworkNamespace(const std::string& path) {
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw minenav::UsageError("--net-namespace " + path + ": " + std::strerror(errno));
  const int rc = setns(fd, CLONE_NEWNET);
  const int error = errno;
  close(fd);
  if (rc != 0)
    throw minenav::UsageError("--net-namespace " + path + ": cannot join (" + std::strerror(error) +
                              "; joining another namespace needs root)");
}

std::map<std::string, minenav::StaticFile> PageFiles() {
  std::map<std::string, minenav::StaticFile> files;
  for (const auto& f : minenav::viewer::embedded::kEmbeddedTexts) {
    const std::string name(f.name);
    if (name == "index") files["/index.html"] = {std::string(f.text), "text/html; charset=utf-8"};
    if (name == "viewer") files["/viewer.js"] = {std::string(f.text), "text/javascript; charset=utf-8"};
  }
  return files;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace minenav;
  std::vector<std::string> args(argv + 1, argv + argc);
  ViewerBridgeOptions options;
  return RunNodeProcess(
      "viewer_bridge", "The operator's view: the bus on a web page and in Foxglove (WebSocket, foxglove.websocket.v1).",
      args, [&](ConfigSchema& s) { DeclareOptions(s, options); },
      [&](NodeRuntime& runtime) {
        if (!runtime.options().log.empty())
          throw UsageError("--log: the bridge shows the live bus; replay a log into it with lcm-logplayer "
                           "(viewer/README.md, \"A recorded log\")");
        if (!options.replay.empty() && options.allow_commands)
          throw UsageError("--allow-commands with --replay: a replayed log takes no commands");
        std::unique_ptr<LogReplay> replay;
        if (!options.replay.empty()) {
          replay = std::make_unique<LogReplay>(options.replay);
          MINENAV_LOG(kInfo) << "replaying " << options.replay << ": " << replay->size() << " messages, "
                             << replay->bytes() / 1000 << " kB, "
                             << static_cast<double>(replay->end_utime() - replay->start_utime()) * 1e-6 << " s";
        }
        std::vector<std::string> publish_topics;
        if (options.allow_commands) publish_topics.push_back(options.command_channel);
        if (replay) publish_topics.push_back(kReplayControlTopic);
        std::map<std::string, std::string> metadata;
        if (options.allow_commands) metadata["command_topic"] = options.command_channel;
        if (replay) metadata["replay_control_topic"] = kReplayControlTopic;
        FoxgloveServer server(options.server, "minenav viewer_bridge", publish_topics, PageFiles(), metadata);
        server.Start();
        MINENAV_LOG(kInfo) << "the operator's view is at http://" << options.server.address << ":" << server.port()
                           << "/ (Foxglove: ws://" << options.server.address << ":" << server.port() << "); commands "
                           << (options.allow_commands ? "ACCEPTED on " + options.command_channel : std::string("refused"));
        if (options.allow_commands && options.server.address != "127.0.0.1" && options.server.address != "::1")
          MINENAV_LOG(kWarn) << "--allow-commands on " << options.server.address
                             << ": anyone who reaches this address can stop or start the vehicle (commands are not signed yet)";
        if (!options.net_namespace.empty()) {
          JoinNetworkNamespace(options.net_namespace);
          MINENAV_LOG(kInfo) << "on the bus of network namespace " << options.net_namespace;
        }
        runtime.Start();
        ViewerBridgeNode node(runtime, options, server, replay.get());
        const int code = node.Run();
        server.Stop();
        return code;
      });
}
