#include "logger/channel_spy.h"

#include <cstdio>

#include "logger/message_catalog.h"

namespace minenav {

namespace {

using nlohmann::json;

std::string Dump(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }

std::string Fit(std::string s, int width) {
  for (char& c : s)
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  if (width > 3 && static_cast<int>(s.size()) > width) s = s.substr(0, static_cast<size_t>(width - 3)) + "...";
  return s;
}

std::string Bytes(int64_t b) {
  char buf[32];
  if (b < 10'000) std::snprintf(buf, sizeof(buf), "%lld B", static_cast<long long>(b));
  else if (b < 10'000'000) std::snprintf(buf, sizeof(buf), "%.1f kB", static_cast<double>(b) / 1e3);
  else std::snprintf(buf, sizeof(buf), "%.1f MB", static_cast<double>(b) / 1e6);
  return buf;
}

}  // namespace

json ShortenArrays(const json& j, size_t keep) {
  if (j.is_array()) {
    json out = json::array();
    for (size_t i = 0; i < j.size() && i < keep; ++i) out.push_back(ShortenArrays(j[i], keep));
    if (j.size() > keep) out.push_back("... " + std::to_string(j.size()) + " in all");
    return out;
  }
  if (j.is_object()) {
    json out = json::object();
    for (const auto& [k, v] : j.items()) out[k] = ShortenArrays(v, keep);
    return out;
  }
  if (j.is_string() && j.get_ref<const std::string&>().size() > 200)
    return j.get_ref<const std::string&>().substr(0, 200) + "...";
  return j;
}

void ChannelSpy::Add(std::string_view channel_view, const uint8_t* data, size_t size, int64_t utime) {
  auto it = channels_.find(channel_view);
  if (it == channels_.end()) it = channels_.emplace(std::string(channel_view), Channel{}).first;
  Channel& c = it->second;
  ++messages_;
  ++c.count;
  c.bytes += static_cast<int64_t>(size);
  c.last_size = static_cast<int64_t>(size);
  c.recent.push_back(utime);
  while (!c.recent.empty() && (c.recent.front() < utime - window_us_ || c.recent.front() > utime)) c.recent.pop_front();
  const MessageProbe probe = ProbeMessage(it->first, data, size);
  if (!probe.type_name.empty()) c.type = probe.type_name;
  if (!probe.ok) {
    ++c.bad;
    c.last_error = probe.error;
    return;
  }
  const KnownMessageType* type = probe.known_type ? FindKnownTypeByName(probe.type_name) : nullptr;
  if (type == nullptr) {
    c.latest = json();
    return;
  }
  json j;
  std::string error;
  if (type->to_json(data, size, &j, &error)) {
    c.latest = ShortenArrays(j);
  } else {
    ++c.bad;
    c.last_error = error;
  }
}

double ChannelSpy::Rate(const Channel& c, int64_t now) const {
  int64_t n = 0;
  for (const int64_t t : c.recent)
    if (t >= now - window_us_ && t <= now) ++n;
  return static_cast<double>(n) / (static_cast<double>(window_us_) * 1e-6);
}

std::string ChannelSpy::Text(int64_t now, int width, int field_lines) const {
  std::string out;
  char line[512];
  std::snprintf(line, sizeof(line), "%-22s %-30s %8s %8s %10s %10s %5s", "channel", "type", "rate Hz", "count",
                "bytes", "last", "bad");
  out += Fit(line, width) + "\n";
  for (const auto& [name, c] : channels_) {
    std::snprintf(line, sizeof(line), "%-22s %-30s %8.1f %8lld %10s %10s %5lld", name.c_str(),
                  c.type.empty() ? "(foreign)" : c.type.c_str(), Rate(c, now), static_cast<long long>(c.count),
                  Bytes(c.bytes).c_str(), Bytes(c.last_size).c_str(), static_cast<long long>(c.bad));
    out += Fit(line, width) + "\n";
    std::string fields = c.latest.is_null() ? std::string() : Dump(c.latest);
    if (c.bad > 0 && !c.last_error.empty()) fields = "last bad: " + c.last_error + "  " + fields;
    const int text_width = std::max(10, width - 4);
    for (int k = 0; k < field_lines && !fields.empty(); ++k) {
      const bool last = k == field_lines - 1;
      std::string piece = fields.substr(0, static_cast<size_t>(text_width));
      fields = fields.size() > piece.size() ? fields.substr(piece.size()) : "";
      if (last && !fields.empty()) piece = piece.substr(0, piece.size() - 3) + "...";
      out += "    " + Fit(piece, text_width) + "\n";
    }
  }
  return out;
}

json ChannelSpy::Json(int64_t now) const {
  json list = json::array();
  for (const auto& [name, c] : channels_)
    list.push_back({{"channel", name},
                    {"type", c.type},
                    {"count", c.count},
                    {"bytes", c.bytes},
                    {"bad", c.bad},
                    {"rate_hz", Rate(c, now)},
                    {"last_error", c.last_error},
                    {"latest", c.latest}});
  return {{"messages", messages_}, {"channels", std::move(list)}};
}

}  // namespace minenav
