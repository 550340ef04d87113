// log_tool export-mcap LOG OUT.mcap: an LCM log as MCAP (logger/README.md, "log_tool
// export-mcap") for Foxglove and Lichtblick. Every channel becomes a topic of the same name
// whose messages are the LCM message's fields as JSON, with the JSON Schema generated from the
// .lcm file (minenav/message_json.hpp; the contour map inflated, as the operator's view shows
// it). Beside them, in Foxglove's well-known schemas (viewer/foxglove_schemas.h), under
// /foxglove/<channel>: poses as foxglove.PoseInFrame, scans as foxglove.LaserScan at the
// vehicle's estimated pose, walls and contour maps as foxglove.SceneUpdate line strips.

#include <cstdio>
#include <map>
#include <optional>

#include "common/config.h"
#include "common/file_io.h"
#include "common/message_auth.h"
#include "common/node/bus.h"
#include "common/node/contour_map_conversions.h"
#include "common/node/conversions.h"
#include "common/node/event_log.h"
#include "logger/log_tool_commands.h"
#include "logger/mcap_writer.h"
#include "logger/message_catalog.h"
#include "minenav/contour_map_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "minenav/vehicle_truth_t.hpp"
#include "viewer/display_stream.h"
#include "viewer/foxglove_schemas.h"

namespace minenav {

namespace {

using nlohmann::json;
namespace fs = foxglove_schemas;

std::string Dump(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }

// Topics and schemas, registered in the MCAP the first time they are used.
class McapTopics {
 public:
  explicit McapTopics(McapWriter& w) : w_(w) {}
  void Write(const std::string& topic, const std::string& schema_name, const std::string& schema, uint64_t log_ns,
             uint64_t publish_ns, const json& message) {
    auto it = channels_.find(topic);
    if (it == channels_.end()) {
      auto s = schemas_.find(schema_name);
      if (s == schemas_.end()) s = schemas_.emplace(schema_name, w_.AddSchema(schema_name, "jsonschema", schema)).first;
      it = channels_.emplace(topic, w_.AddChannel(s->second, topic, "json")).first;
    }
    w_.AddMessage(it->second, log_ns, publish_ns, Dump(message));
  }

 private:
  McapWriter& w_;
  std::map<std::string, uint16_t> schemas_, channels_;
};

template <typename T>
T Decode(const LogEvent& e) {
  T m{};
  std::string error;
  if (!DecodeMessage(e.data.data(), static_cast<int>(e.data.size()), e.channel, &m, &error)) throw InputError(error);
  return m;
}

}  // namespace

int RunExportMcapCommand(const std::vector<std::string>& in_args) {
  std::string channels = ".*", scan_pose_channel = "POSE";
  bool foxglove = true;
  int chunk_kb = 1024;
  ConfigSchema schema("log_tool export-mcap",
                      "Writes an LCM log as MCAP for Foxglove and Lichtblick: every channel as a topic of its\n"
                      "own with the message's fields as JSON (JSON Schema from the .lcm file), and poses, scans\n"
                      "and maps also in Foxglove's schemas under /foxglove/<channel>. Messages that do not decode\n"
                      "are skipped and counted (one line on stderr).");
  schema.SetPositional("LOG OUT.mcap", 2, 2);
  schema.AddString("channels", &channels, "regex of the channels to export (LCM syntax, whole name)");
  schema.AddBool("foxglove", &foxglove, "also write poses, scans and maps in Foxglove's well-known schemas");
  schema.AddString("scan_pose_channel", &scan_pose_channel,
                   "pose_estimate_t channel whose latest pose places the Foxglove scans (else SIM_TRUTH, else the vehicle frame)");
  schema.AddInt("chunk_kb", &chunk_kb, "KB of messages per MCAP chunk (the unit readers index and load)", 1, 1 << 20);
  if (schema.Parse(in_args) == ParseOutcome::kExit) return 0;
  const std::string log = schema.positional()[0], out = schema.positional()[1];
  ValidateChannelPattern(channels);
  CheckOutputIsNotInput("OUT.mcap", out, {log});
  const ChannelMatcher matcher(channels);

  LogReader reader(log);
  McapWriter writer(out, static_cast<size_t>(chunk_kb) * 1024);
  McapTopics topics(writer);
  std::optional<pose2d_t> estimate, truth;
  int64_t skipped = 0, foreign = 0;
  std::string first_error;
  while (const LogEvent* e = reader.NextInPlace()) {
    if (!matcher.Matches(e->channel)) continue;
    const uint64_t log_ns = static_cast<uint64_t>(std::max<int64_t>(0, e->timestamp)) * 1000u;
    // The message without a signed command's authentication trailer (common/message_auth.h).
    const size_t size = static_cast<size_t>(StripAuthTrailer(e->data.data(), static_cast<int>(e->data.size())));
    const MessageProbe probe = ProbeMessage(e->channel, e->data.data(), size);
    if (!probe.ok || !probe.known_type) {
      if (!probe.ok) {
        if (first_error.empty()) first_error = e->channel + " at byte " + std::to_string(e->offset) + ": " + probe.error;
        ++skipped;
      } else {
        ++foreign;
      }
      continue;
    }
    const uint64_t publish_ns = probe.utime && *probe.utime >= 0 ? static_cast<uint64_t>(*probe.utime) * 1000u : log_ns;
    const std::string& type = probe.type_name;
    try {
      if (type == "minenav.contour_map_t") {
        const ContourMapMessage map = ContourMapFromLcm(Decode<contour_map_t>(*e));
        topics.Write(e->channel, kContourMapJsonName, kContourMapJsonSchema, log_ns, publish_ns, ContourMapJson(map));
      } else {
        json j;
        std::string error;
        const KnownMessageType* known = FindKnownTypeByName(type);
        if (!known->to_json(e->data.data(), size, &j, &error)) throw InputError(error);
        topics.Write(e->channel, type, std::string(known->json_schema), log_ns, publish_ns, j);
      }
      if (type == "minenav.pose_estimate_t" && e->channel == scan_pose_channel) estimate = Decode<pose_estimate_t>(*e).pose;
      if (type == "minenav.vehicle_truth_t") truth = Decode<vehicle_truth_t>(*e).pose;
      if (!foxglove) continue;
      if (auto f = fs::ToFoxglove(e->channel, type, e->data.data(), size, estimate ? estimate : truth))
        topics.Write("/foxglove/" + e->channel, f->first, fs::SchemaText(f->first), log_ns, publish_ns, f->second);
    } catch (const InputError& ex) {
      if (first_error.empty()) first_error = e->channel + " at byte " + std::to_string(e->offset) + ": " + ex.what();
      ++skipped;
    }
  }
  writer.Close();
  if (skipped > 0)
    std::fprintf(stderr, "log_tool export-mcap: %lld messages skipped (do not decode); the first: %s\n",
                 static_cast<long long>(skipped), first_error.c_str());
  std::fprintf(stderr, "log_tool export-mcap: %llu messages -> %s (%lld of foreign types not exported)\n",
               static_cast<unsigned long long>(writer.messages()), out.c_str(), static_cast<long long>(foreign));
  return 0;
}

}  // namespace minenav
