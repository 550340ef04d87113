#include "viewer/display_stream.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <nlohmann/json.hpp>

#include "common/file_io.h"
#include "common/node/contour_map_conversions.h"
#include "common/node/conversions.h"
#include "logger/message_catalog.h"
#include "minenav/contour_map_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/message_json.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "viewer/foxglove_schemas.h"

namespace minenav {
namespace {

using nlohmann::json;

// JSON text that never throws on a string that is not UTF-8 (a hostile heartbeat message).
std::string Dump(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }

// Metres to the millimetre, radians to the microradian: what a screen can show, in fewer bytes.
double Millimetres(double v) { return std::round(v * 1000.0) / 1000.0; }

constexpr const char* kScanSchema = R"js({"type":"object","title":"minenav.viewer.scan",)js"
    R"js("description":"a ladar scan decimated for display: reading i at bearing start_angle + i * angle_step (rad, sensor frame), range in m (null = no return)",)js"
    R"js("properties":{"utime":{"type":"integer"},"scan_id":{"type":"integer"},"sensor_id":{"type":"string"},)js"
    R"js("sensor_offset":{"type":"object","properties":{"x":{"type":"number"},"y":{"type":"number"},"theta":{"type":"number"}}},)js"
    R"js("start_angle":{"type":"number"},"angle_step":{"type":"number"},"stride":{"type":"integer"},)js"
    R"js("num_readings":{"type":"integer"},"ranges":{"type":"array","items":{"type":["number","null"]}}},)js"
    R"js("required":["utime","scan_id","start_angle","angle_step","ranges"]})js";

constexpr const char* kContourMapSchemaText = R"js({"type":"object","title":"minenav.viewer.contour_map",)js"
    R"js("description":"the contour map, inflated: each contour's points as a flat list x0, y0, x1, y1, ... (m, map frame)",)js"
    R"js("properties":{"utime":{"type":"integer"},"version":{"type":"integer"},"num_scans":{"type":"integer"},)js"
    R"js("contours":{"type":"array","items":{"type":"object","properties":{"id":{"type":"integer"},)js"
    R"js("closed":{"type":"boolean"},"xy":{"type":"array","items":{"type":"number"}}}}}},)js"
    R"js("required":["utime","version","contours"]})js";

constexpr const char* kFleetSchema = R"js({"type":"object","title":"minenav.viewer.fleet",)js"
    R"js("description":"every process seen on HEARTBEAT: age of its last heartbeat (s), state, messages handled and rejected per second over its last heartbeat interval",)js"
    R"js("properties":{"utime":{"type":"integer"},"stale_after_s":{"type":"number"},"processes":{"type":"array","items":{"type":"object",)js"
    R"js("properties":{"process":{"type":"string"},"instance":{"type":"string"},"pid":{"type":"integer"},)js"
    R"js("state":{"type":"string"},"message":{"type":"string"},"age_s":{"type":"number"},"stale":{"type":"boolean"},)js"
    R"js("messages_in":{"type":"integer"},"messages_bad":{"type":"integer"},)js"
    R"js("in_rate_hz":{"type":["number","null"]},"bad_rate_hz":{"type":["number","null"]}}}}},"required":["utime","processes"]})js";

constexpr const char* kViewerConfigSchema = R"js({"type":"object","title":"minenav.viewer.config",)js"
    R"js("properties":{"vehicle_width_m":{"type":"number"},"vehicle_length_m":{"type":"number"}},)js"
    R"js("required":["vehicle_width_m","vehicle_length_m"]})js";

std::string StateName(int8_t state) {
  switch (state) {
    case heartbeat_t::STARTING: return "STARTING";
    case heartbeat_t::OK: return "OK";
    case heartbeat_t::WARN: return "WARN";
    case heartbeat_t::ERROR: return "ERROR";
    case heartbeat_t::STOPPING: return "STOPPING";
    default: return "state " + std::to_string(state);
  }
}

// Types whose messages are state rather than a stream.
bool IsLatched(const std::string& type_name) {
  return type_name == "minenav.line_map_t" || type_name == "minenav.path_t" ||
         type_name == "minenav.mission_status_t" || type_name == "minenav.task_plan_t";
}

}  // namespace

const char* const kContourMapJsonSchema = kContourMapSchemaText;

json ContourMapJson(const ContourMapMessage& map) {
  json contours = json::array();
  for (const ContourPolyline& c : map.contours) {
    json xy = json::array();
    for (const Eigen::Vector2d& p : c.points) {
      xy.push_back(Millimetres(p.x()));
      xy.push_back(Millimetres(p.y()));
    }
    contours.push_back({{"id", c.id}, {"closed", c.closed}, {"xy", std::move(xy)}});
  }
  return {{"utime", map.utime}, {"version", map.version}, {"num_scans", map.num_scans}, {"contours", std::move(contours)}};
}

void DeclareOptions(OptionScope s, DisplayOptions& o) {
  s.AddInt("max_scan_points", &o.max_scan_points, "readings of a displayed scan (every k-th reading is sent)", 8,
           100000);
  s.AddDouble("max_scan_rate", &o.max_scan_rate, "Hz", "displayed scans per second", 0.1, 100.0);
  s.AddDouble("max_channel_rate", &o.max_channel_rate, "Hz",
              "messages per second of any other channel (poses, commands, ...); 0 = no limit", 0.0, 1000.0);
  s.AddDouble("stale_after", &o.stale_after, "s", "a process whose last heartbeat is older is shown stale", 0.1,
              3600.0);
  s.AddDouble("vehicle_width", &o.vehicle_width, "m", "width of the vehicle polygon drawn at the pose", 0.1, 50.0);
  s.AddDouble("vehicle_length", &o.vehicle_length, "m", "length of the vehicle polygon (centred on the pose)", 0.1,
              100.0);
}

DisplayStream::DisplayStream(DisplayOptions options) : options_(options) {}

bool DisplayStream::Throttle(const std::string& topic, double rate, int64_t now) {
  if (rate <= 0.0) return false;
  const auto it = last_sent_.find(topic);
  const int64_t min_gap_us = static_cast<int64_t>(1e6 / rate);
  // A clock that went back (a log replayed again) starts the topic afresh.
  if (it != last_sent_.end() && now >= it->second && now - it->second < min_gap_us) {
    ++counters_.throttled;
    return true;
  }
  last_sent_[topic] = now;
  return false;
}

std::optional<DisplayMessage> DisplayStream::OnMessage(std::string_view channel_view, const uint8_t* data,
                                                       size_t size, int64_t receive_utime) {
  const std::string channel(channel_view);
  std::string type_name = ExpectedTypeForChannel(channel);
  const KnownMessageType* type =
      type_name.empty() ? FindKnownTypeByFingerprint(data, size) : FindKnownTypeByName(type_name);
  if (type == nullptr) {
    ++counters_.foreign;
    return std::nullopt;
  }
  type_name = type->name;
  std::optional<DisplayMessage> out;
  if (type_name == "minenav.ladar_scan_t") {
    out = Scan(channel, data, size, receive_utime);
  } else if (type_name == "minenav.contour_map_t") {
    out = ContourMap(channel, data, size);
  } else {
    json j;
    std::string error;
    if (!type->to_json(data, size, &j, &error)) throw InputError("channel " + channel + ": " + error);
    if (type_name == "minenav.heartbeat_t") {
      heartbeat_t m{};
      DecodeMessage(data, static_cast<int>(size), channel, &m, &error);
      Heartbeat(m, receive_utime);
    }
    if (type_name == "minenav.line_map_t") {
      const int64_t version = j.value("version", int64_t{0});
      const auto it = last_version_.find(channel);
      if (it != last_version_.end() && it->second == version) {
        ++counters_.unchanged;
        return std::nullopt;
      }
      last_version_[channel] = version;
    } else if (!IsLatched(type_name) && type_name != "minenav.heartbeat_t" &&
               type_name != "minenav.coordinator_command_t" && type_name != "minenav.task_status_t" &&
               Throttle(channel, options_.max_channel_rate, receive_utime)) {
      return std::nullopt;
    }
    DisplayMessage m;
    m.topic = channel;
    m.schema_name = type_name;
    m.schema = std::string(type->json_schema);
    m.utime = j.value("utime", receive_utime);
    m.payload = Dump(j);
    m.latched = IsLatched(type_name);
    out = std::move(m);
  }
  if (out) ++counters_.shown;
  return out;
}

std::vector<DisplayMessage> DisplayStream::OnMessageWithFoxglove(std::string_view channel_view, const uint8_t* data,
                                                                 size_t size, int64_t receive_utime) {
  std::vector<DisplayMessage> out;
  std::optional<DisplayMessage> d = OnMessage(channel_view, data, size, receive_utime);
  if (!d) return out;
  const std::string channel(channel_view);
  const std::string type = d->schema_name == "minenav.viewer.scan"  ? "minenav.ladar_scan_t"
                           : d->schema_name == kContourMapJsonName ? "minenav.contour_map_t"
                                                                   : d->schema_name;
  if (channel == "POSE" && type == "minenav.pose_estimate_t") {
    pose_estimate_t m{};
    std::string error;
    if (DecodeMessage(data, static_cast<int>(size), channel, &m, &error)) latest_pose_ = m.pose;
  }
  // The page's scan shows every stride-th reading; Foxglove gets the same ones.
  const size_t stride = type == "minenav.ladar_scan_t" ? json::parse(d->payload)["stride"].get<size_t>() : 1;
  if (auto f = foxglove_schemas::ToFoxglove(channel, type, data, size, latest_pose_, stride)) {
    DisplayMessage m;
    m.topic = "/foxglove/" + channel;
    m.schema_name = f->first;
    m.schema = foxglove_schemas::SchemaText(f->first);
    m.payload = Dump(f->second);
    m.utime = d->utime;
    m.latched = d->latched;
    out.push_back(std::move(*d));
    out.push_back(std::move(m));
  } else {
    out.push_back(std::move(*d));
  }
  return out;
}

std::optional<DisplayMessage> DisplayStream::Scan(const std::string& channel, const uint8_t* data, size_t size,
                                                  int64_t now) {
  ladar_scan_t m{};
  std::string error;
  if (!DecodeMessage(data, static_cast<int>(size), channel, &m, &error)) throw InputError(error);
  if (Throttle(channel, options_.max_scan_rate, now)) return std::nullopt;
  const size_t n = m.ranges.size();
  const size_t stride = std::max<size_t>(1, (n + static_cast<size_t>(options_.max_scan_points) - 1) /
                                                static_cast<size_t>(options_.max_scan_points));
  json ranges = json::array();
  for (size_t i = 0; i < n; i += stride) {
    const double r = m.ranges[i];
    const bool valid = std::isfinite(r) && r > 0.0 && r >= m.min_range && r <= m.max_range;
    ranges.push_back(valid ? json(Millimetres(r)) : json(nullptr));
  }
  json j = {{"utime", m.utime},
            {"scan_id", m.scan_id},
            {"sensor_id", m.sensor_id},
            {"sensor_offset",
             {{"x", m.sensor_offset.x}, {"y", m.sensor_offset.y}, {"theta", m.sensor_offset.theta}}},
            {"start_angle", m.start_angle},
            {"angle_step", static_cast<double>(m.angle_step) * static_cast<double>(stride)},
            {"stride", stride},
            {"num_readings", n},
            {"ranges", std::move(ranges)}};
  DisplayMessage d;
  d.topic = channel;
  d.schema_name = "minenav.viewer.scan";
  d.schema = kScanSchema;
  d.payload = Dump(j);
  d.utime = m.utime;
  return d;
}

std::optional<DisplayMessage> DisplayStream::ContourMap(const std::string& channel, const uint8_t* data,
                                                        size_t size) {
  contour_map_t m{};
  std::string error;
  if (!DecodeMessage(data, static_cast<int>(size), channel, &m, &error)) throw InputError(error);
  const auto it = last_version_.find(channel);
  if (it != last_version_.end() && it->second == m.version) {
    ++counters_.unchanged;
    return std::nullopt;
  }
  const ContourMapMessage map = ContourMapFromLcm(m);  // inflates; throws InputError
  last_version_[channel] = m.version;
  const json j = ContourMapJson(map);
  DisplayMessage d;
  d.topic = channel;
  d.schema_name = kContourMapJsonName;
  d.schema = kContourMapJsonSchema;
  d.payload = Dump(j);
  d.utime = map.utime;
  d.latched = true;
  return d;
}

void DisplayStream::Heartbeat(const heartbeat_t& m, int64_t now) {
  Process& p = processes_[m.process + "/" + m.instance];
  if (p.received != 0) {
    p.previous_utime = p.last.utime;
    p.previous_in = p.last.messages_in;
    p.previous_bad = p.last.messages_bad;
    p.has_previous = true;
  }
  p.last = m;
  p.received = now;
}

DisplayMessage DisplayStream::FleetTable(int64_t now) const {
  json rows = json::array();
  for (const auto& [key, p] : processes_) {
    const double age = static_cast<double>(now - p.received) * 1e-6;
    json in_rate = nullptr, bad_rate = nullptr;
    const double dt = static_cast<double>(p.last.utime - p.previous_utime) * 1e-6;
    // A restarted process counts from 0 again: no rate until two heartbeats of it.
    if (p.has_previous && dt > 0.0 && p.last.messages_in >= p.previous_in && p.last.messages_bad >= p.previous_bad) {
      in_rate = std::round(static_cast<double>(p.last.messages_in - p.previous_in) / dt * 10.0) / 10.0;
      bad_rate = std::round(static_cast<double>(p.last.messages_bad - p.previous_bad) / dt * 10.0) / 10.0;
    }
    rows.push_back({{"process", p.last.process},
                    {"instance", p.last.instance},
                    {"pid", p.last.pid},
                    {"state", StateName(p.last.state)},
                    {"message", p.last.message},
                    {"age_s", std::round(age * 10.0) / 10.0},
                    {"stale", age > options_.stale_after},
                    {"messages_in", p.last.messages_in},
                    {"messages_bad", p.last.messages_bad},
                    {"in_rate_hz", in_rate},
                    {"bad_rate_hz", bad_rate}});
  }
  DisplayMessage d;
  d.topic = kFleetTopic;
  d.schema_name = "minenav.viewer.fleet";
  d.schema = kFleetSchema;
  d.payload = Dump({{"utime", now}, {"stale_after_s", options_.stale_after}, {"processes", std::move(rows)}});
  d.utime = now;
  d.latched = true;
  return d;
}

DisplayMessage DisplayStream::ViewerConfig() const {
  DisplayMessage d;
  d.topic = kViewerConfigTopic;
  d.schema_name = "minenav.viewer.config";
  d.schema = kViewerConfigSchema;
  d.payload = Dump({{"vehicle_width_m", options_.vehicle_width}, {"vehicle_length_m", options_.vehicle_length}});
  d.latched = true;
  return d;
}

}  // namespace minenav
