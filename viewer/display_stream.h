#pragma once
// What the operator's view shows, made from the bus's messages: each decoded message
// becomes one JSON message on a topic of the page (viewer/README.md, "Topics"), or none
// when it would only cost bandwidth. No sockets, no threads, no clock: the bridge node
// calls it on the bus thread and hands what it returns to the WebSocket server.
//
// Bandwidth rules (issue 17): a scan is decimated to at most max_scan_points readings and
// sent at most max_scan_rate times a second; the contour map (inflated from its zlib form)
// and the walls are sent only when their version changes; every other channel at most
// max_channel_rate times a second. HEARTBEAT becomes the fleet table (age, state, rates).

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/config.h"
#include "common/node/contour_map_conversions.h"
#include "minenav/heartbeat_t.hpp"
#include "minenav/pose2d_t.hpp"

namespace minenav {

struct DisplayOptions {
  int max_scan_points = 360;       // readings of a displayed scan (every k-th reading)
  double max_scan_rate = 5.0;      // Hz: displayed scans per second
  double max_channel_rate = 10.0;  // Hz: messages per second of any other channel; 0 = no limit
  double stale_after = 3.0;        // s: a process whose heartbeat is older is shown stale
  double vehicle_width = 3.3;      // m: the vehicle polygon drawn at the pose (centred on it)
  double vehicle_length = 10.0;    // m
};
void DeclareOptions(OptionScope scope, DisplayOptions& o);

// One message for the page (and for Foxglove): JSON on a topic with its JSON Schema.
struct DisplayMessage {
  std::string topic;
  std::string schema_name;
  std::string schema;   // JSON Schema text
  std::string payload;  // JSON text (UTF-8)
  int64_t utime = 0;    // us: the message's own time
  // State rather than a stream (map, walls, path, mission, fleet): the server keeps the
  // newest and sends it to a client that subscribes later or missed it while slow.
  bool latched = false;
};

struct DisplayCounters {
  int64_t shown = 0;      // messages turned into display messages
  int64_t throttled = 0;  // skipped by the rate limits
  int64_t unchanged = 0;  // maps and walls whose version had not changed
  int64_t foreign = 0;    // channels of no minenav type (not shown)
};

// The topics the stream makes besides the bus's channel names.
inline constexpr const char* kFleetTopic = "/minenav/fleet";
inline constexpr const char* kViewerConfigTopic = "/minenav/viewer_config";

// The contour map as the page (and the MCAP export) shows it: inflated, each contour's points
// as a flat list x0, y0, x1, y1, ... to the millimetre. Schema name and text below.
nlohmann::json ContourMapJson(const ContourMapMessage& map);
inline constexpr const char* kContourMapJsonName = "minenav.viewer.contour_map";
extern const char* const kContourMapJsonSchema;

class DisplayStream {
 public:
  explicit DisplayStream(DisplayOptions options);

  // A message received on `channel` at receive_utime (us). Returns the display message to
  // send, or nullopt (throttled, unchanged, foreign). Throws InputError (one line naming
  // the channel) when a minenav payload does not decode or is invalid.
  std::optional<DisplayMessage> OnMessage(std::string_view channel, const uint8_t* data, size_t size,
                                          int64_t receive_utime);
  // With each display message of a pose, scan, map or walls, the same in Foxglove's
  // well-known schema on "/foxglove/<channel>" (foxglove_schemas.h), so Foxglove's 3D panel
  // draws the live bus: PoseInFrame, LaserScan (decimated like the page's, at the latest POSE),
  // SceneUpdate line strips. Empty when the message is not shown.
  std::vector<DisplayMessage> OnMessageWithFoxglove(std::string_view channel, const uint8_t* data, size_t size,
                                                    int64_t receive_utime);

  // The fleet table at `now`: one row per process and instance seen on HEARTBEAT.
  DisplayMessage FleetTable(int64_t now) const;
  // The page's settings (vehicle size, units): latched, sent once.
  DisplayMessage ViewerConfig() const;

  const DisplayCounters& counters() const { return counters_; }

 private:
  struct Process {
    heartbeat_t last{};
    int64_t received = 0;  // us
    // The heartbeat before, for rates over the last interval.
    int64_t previous_utime = 0, previous_in = 0, previous_bad = 0;
    bool has_previous = false;
  };
  bool Throttle(const std::string& topic, double rate, int64_t now);
  std::optional<DisplayMessage> Scan(const std::string& channel, const uint8_t* data, size_t size, int64_t now);
  std::optional<DisplayMessage> ContourMap(const std::string& channel, const uint8_t* data, size_t size);
  void Heartbeat(const heartbeat_t& m, int64_t now);

  DisplayOptions options_;
  DisplayCounters counters_;
  std::optional<pose2d_t> latest_pose_;  // POSE, for the Foxglove scans
  std::map<std::string, int64_t> last_sent_;      // topic -> receive utime of the last message sent
  std::map<std::string, int64_t> last_version_;   // topic -> version of the map or walls sent
  std::map<std::string, Process> processes_;      // "process/instance"
};

}  // namespace minenav
