#include "logger/log_summary.h"

#include <algorithm>
#include <iomanip>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/file_io.h"
#include "logger/strict_log_reader.h"
#include "logger/message_catalog.h"

namespace minenav {

int64_t LogSummary::total_decode_errors() const {
  int64_t n = 0;
  for (const auto& c : channels) n += c.decode_errors;
  return n;
}

LogSummary SummarizeLog(const std::string& path) {
  LogSummary summary;
  summary.path = path;
  StrictLogReader reader(path);
  summary.file_bytes = reader.file_size();
  std::map<std::string, ChannelSummary> channels;
  LogRecord rec;
  while (true) {
    try {
      if (!reader.Next(&rec)) break;
    } catch (const InputError& e) {
      summary.file_error = e.what();
      break;
    }
    if (summary.events == 0) summary.first_timestamp = rec.timestamp;
    summary.last_timestamp = rec.timestamp;
    ++summary.events;
    ChannelSummary& c = channels[rec.channel];
    if (c.count == 0) {
      c.channel = rec.channel;
      c.first_timestamp = rec.timestamp;
    }
    ++c.count;
    c.bytes += static_cast<int64_t>(rec.data.size());
    c.last_timestamp = rec.timestamp;
    const MessageProbe probe = ProbeMessage(rec.channel, rec.data.data(), rec.data.size());
    if (c.type.empty()) c.type = probe.type_name;
    if (!probe.ok) {
      if (c.decode_errors++ == 0)
        c.first_error = "channel " + rec.channel + ", event " + std::to_string(rec.eventnum) + " at byte " +
                        std::to_string(rec.offset) + ": " + probe.error;
      continue;
    }
    if (probe.utime) {
      if (!c.first_utime) c.first_utime = probe.utime;
      c.last_utime = probe.utime;
    }
    if (probe.sequence) {
      c.sequence_field = probe.sequence_field;
      const int64_t s = *probe.sequence;
      if (c.last_sequence) {
        const int64_t prev = *c.last_sequence;
        if (s > prev + 1) {
          ++c.sequence_gaps;
          c.missing += s - prev - 1;
        } else if (s <= prev) {
          ++c.out_of_order;
        }
      } else {
        c.first_sequence = s;
      }
      c.last_sequence = s;
    }
  }
  for (auto& [name, c] : channels) {
    if (c.count > 1 && c.last_timestamp > c.first_timestamp)
      c.rate_hz = static_cast<double>(c.count - 1) * 1e6 / static_cast<double>(c.last_timestamp - c.first_timestamp);
    summary.channels.push_back(c);
  }
  return summary;
}

namespace {

std::string FormatSeconds(int64_t utime_delta) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(3) << static_cast<double>(utime_delta) * 1e-6 << " s";
  return os.str();
}

}  // namespace

std::string FormatLogSummary(const LogSummary& s) {
  std::ostringstream os;
  os << s.path << ": " << s.events << " events, " << s.file_bytes << " bytes";
  if (s.events > 0) {
    os << ", log time " << s.first_timestamp << " .. " << s.last_timestamp << " us ("
       << FormatSeconds(s.last_timestamp - s.first_timestamp) << ")";
  }
  os << "\n";
  if (!s.file_error.empty()) os << "FILE DAMAGED: " << s.file_error << "\n";
  os << "\n"
     << std::left << std::setw(20) << "channel" << std::setw(26) << "type" << std::right << std::setw(8)
     << "count" << std::setw(12) << "bytes" << std::setw(9) << "rate Hz" << std::setw(18) << "first utime"
     << std::setw(18) << "last utime" << std::setw(8) << "errors" << std::setw(8) << "gaps" << std::setw(9)
     << "missing" << "\n";
  for (const auto& c : s.channels) {
    os << std::left << std::setw(20) << c.channel << std::setw(26) << (c.type.empty() ? "(foreign)" : c.type)
       << std::right << std::setw(8) << c.count << std::setw(12) << c.bytes << std::setw(9) << std::fixed
       << std::setprecision(2) << c.rate_hz << std::setw(18)
       << (c.first_utime ? std::to_string(*c.first_utime) : "-") << std::setw(18)
       << (c.last_utime ? std::to_string(*c.last_utime) : "-") << std::setw(8) << c.decode_errors << std::setw(8)
       << (c.sequence_field.empty() ? "-" : std::to_string(c.sequence_gaps)) << std::setw(9)
       << (c.sequence_field.empty() ? "-" : std::to_string(c.missing)) << "\n";
  }
  bool any_detail = false;
  for (const auto& c : s.channels) {
    if (c.decode_errors > 0) {
      if (!any_detail) os << "\n";
      any_detail = true;
      os << "decode errors: " << c.decode_errors << " on " << c.channel << "; first: " << c.first_error << "\n";
    }
    if (!c.sequence_field.empty() && (c.sequence_gaps > 0 || c.out_of_order > 0)) {
      if (!any_detail) os << "\n";
      any_detail = true;
      os << c.channel << ": " << c.sequence_field << " " << *c.first_sequence << " .. " << *c.last_sequence
         << ", " << c.sequence_gaps << " gaps (" << c.missing << " missing), " << c.out_of_order
         << " out of order\n";
    }
  }
  return os.str();
}

std::string LogSummaryToJson(const LogSummary& s) {
  nlohmann::json j;
  j["path"] = s.path;
  j["file_bytes"] = s.file_bytes;
  j["events"] = s.events;
  j["first_timestamp"] = s.first_timestamp;
  j["last_timestamp"] = s.last_timestamp;
  j["file_error"] = s.file_error;
  j["decode_errors"] = s.total_decode_errors();
  j["channels"] = nlohmann::json::array();
  for (const auto& c : s.channels) {
    nlohmann::json cj;
    cj["channel"] = c.channel;
    cj["type"] = c.type;
    cj["count"] = c.count;
    cj["bytes"] = c.bytes;
    cj["rate_hz"] = c.rate_hz;
    cj["first_timestamp"] = c.first_timestamp;
    cj["last_timestamp"] = c.last_timestamp;
    cj["first_utime"] = c.first_utime ? nlohmann::json(*c.first_utime) : nlohmann::json();
    cj["last_utime"] = c.last_utime ? nlohmann::json(*c.last_utime) : nlohmann::json();
    cj["decode_errors"] = c.decode_errors;
    cj["first_error"] = c.first_error;
    cj["sequence_field"] = c.sequence_field;
    cj["first_sequence"] = c.first_sequence ? nlohmann::json(*c.first_sequence) : nlohmann::json();
    cj["last_sequence"] = c.last_sequence ? nlohmann::json(*c.last_sequence) : nlohmann::json();
    cj["sequence_gaps"] = c.sequence_gaps;
    cj["missing"] = c.missing;
    cj["out_of_order"] = c.out_of_order;
    j["channels"].push_back(cj);
  }
  return j.dump(2) + "\n";
}

}  // namespace minenav
