#include "fleet/status_table.h"

#include <algorithm>

#include "fleet/number_text.h"

namespace minenav {

namespace {

// A heartbeat's message is one line, but may be long: the table keeps its start.
constexpr size_t kMessageWidth = 60;

std::string Shorten(const std::string& text, size_t width) {
  return text.size() <= width ? text : text.substr(0, width - 3) + "...";
}

// Age, state, rate and message of a heartbeat ("-" for each when none was heard).
std::vector<std::string> HeartbeatCells(const std::optional<HeartbeatRecord>& hb, int64_t now) {
  if (!hb) return {"-", "-", "-", ""};
  return {FixedText(hb->age_s(now), 1) + " s", ToString(hb->last.state),
          hb->messages_per_s ? FixedText(*hb->messages_per_s, 1) : "-", Shorten(hb->last.message, kMessageWidth)};
}

}  // namespace

std::string FormatTable(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
  std::vector<size_t> widths(header.size(), 0);
  for (size_t c = 0; c < header.size(); ++c) widths[c] = header[c].size();
  for (const auto& row : rows)
    for (size_t c = 0; c < row.size() && c < widths.size(); ++c) widths[c] = std::max(widths[c], row[c].size());
  auto line = [&](const std::vector<std::string>& cells) {
    std::string out;
    for (size_t c = 0; c < cells.size() && c < widths.size(); ++c) {
      out += cells[c];
      if (c + 1 < cells.size()) out += std::string(widths[c] - cells[c].size() + 2, ' ');
    }
    while (!out.empty() && out.back() == ' ') out.pop_back();
    return out + "\n";
  };
  std::string text = line(header);
  for (const auto& row : rows) text += line(row);
  return text;
}

std::string FleetStatusTable(const std::vector<ProcessStatus>& rows, int64_t now) {
  std::vector<std::vector<std::string>> cells;
  for (const ProcessStatus& r : rows) {
    std::vector<std::string> row = {r.name, r.group, r.state_text, r.pid > 0 ? std::to_string(r.pid) : "-",
                                    std::to_string(r.restarts)};
    for (std::string& c : HeartbeatCells(r.heartbeat, now)) row.push_back(std::move(c));
    cells.push_back(std::move(row));
  }
  return FormatTable({"process", "group", "state", "pid", "restarts", "heartbeat", "hb state", "msgs/s", "message"},
                     cells);
}

std::string BusStatusTable(const HeartbeatMonitor& heartbeats, int64_t now) {
  std::vector<std::vector<std::string>> cells;
  for (const HeartbeatRecord* hb : heartbeats.All()) {
    const HeartbeatSample& s = hb->last;
    cells.push_back({s.instance.empty() ? s.process : s.process + ":" + s.instance, std::to_string(s.pid),
                     FixedText(hb->age_s(now), 1) + " s", ToString(s.state),
                     hb->messages_per_s ? FixedText(*hb->messages_per_s, 1) : "-", std::to_string(s.messages_bad),
                     Shorten(s.message, kMessageWidth)});
  }
  return FormatTable({"process", "pid", "heartbeat", "state", "msgs/s", "bad", "message"}, cells);
}

}  // namespace minenav
