#include "logger/log_summary.h"

#include <algorithm>
#include <iomanip>
#include <map>
#include <set>
#include <tuple>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/file_io.h"
#include "common/message_auth.h"
#include "logger/strict_log_reader.h"
#include "logger/message_catalog.h"

namespace minenav {

void SequenceGaps::Add(int64_t n) {
  if (last) {
    if (n > *last + 1) {
      ++gaps;
      missing += n - *last - 1;
    } else if (n <= *last) {
      ++out_of_order;
    }
  } else {
    first = n;
  }
  last = n;
}

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
  // One sequence per publisher of a channel: (channel, signed, sender); unsigned: sender 0.
  std::map<std::tuple<std::string, bool, uint64_t>, SequenceGaps> streams;
  std::map<uint64_t, size_t> sender_index;  // sender -> summary.senders
  std::map<uint64_t, std::set<std::string>> sender_channels;
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
    AuthTrailer trailer;
    const bool is_signed = ParseAuthTrailer(rec.data.data(), static_cast<int>(rec.data.size()), &trailer);
    if (is_signed) {
      auto [it, fresh] = sender_index.try_emplace(trailer.sender, summary.senders.size());
      if (fresh) {
        summary.senders.emplace_back();
        summary.senders.back().sender = trailer.sender;
      }
      SenderSummary& sender = summary.senders[it->second];
      ++sender.count;
      sender.trailer_seq.Add(static_cast<int64_t>(trailer.seq));
      sender_channels[trailer.sender].insert(rec.channel);
    } else {
      ++c.unsigned_count;
    }
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
      if (!c.first_sequence) c.first_sequence = *probe.sequence;
      c.last_sequence = *probe.sequence;
      streams[{rec.channel, is_signed, is_signed ? trailer.sender : 0}].Add(*probe.sequence);
    }
  }
  for (const auto& [key, gaps] : streams) {
    ChannelSummary& c = channels[std::get<0>(key)];
    c.sequence_gaps += gaps.gaps;
    c.missing += gaps.missing;
    c.out_of_order += gaps.out_of_order;
  }
  for (const auto& [sender, names] : sender_channels) {
    summary.senders[sender_index[sender]].channels.assign(names.begin(), names.end());
    for (const std::string& name : names) ++channels[name].signed_senders;
  }
  for (auto& [name, c] : channels) {
    if (c.count > 1 && c.last_timestamp > c.first_timestamp)
      c.rate_hz = static_cast<double>(c.count - 1) * 1e6 / static_cast<double>(c.last_timestamp - c.first_timestamp);
    summary.channels.push_back(c);
  }
  return summary;
}

namespace {

std::string SenderHex(uint64_t sender) {
  std::ostringstream os;
  os << std::hex << std::setw(16) << std::setfill('0') << sender;
  return os.str();
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ",") + n;
  return out;
}

int64_t Publishers(const ChannelSummary& c) { return c.signed_senders + (c.unsigned_count > 0 ? 1 : 0); }

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
  if (!s.senders.empty()) {
    os << "\nsigned senders (authentication trailers, not verified: one sequence over each sender's signed "
          "channels)\n"
       << std::left << std::setw(18) << "sender" << std::right << std::setw(9) << "messages" << std::setw(22)
       << "trailer seq" << std::setw(7) << "gaps" << std::setw(9) << "missing" << std::setw(14) << "out of order"
       << "  channels\n";
    for (const SenderSummary& r : s.senders) {
      const std::string range = std::to_string(*r.trailer_seq.first) + " .. " + std::to_string(*r.trailer_seq.last);
      os << std::left << std::setw(18) << SenderHex(r.sender) << std::right << std::setw(9) << r.count
         << std::setw(22) << range << std::setw(7) << r.trailer_seq.gaps << std::setw(9) << r.trailer_seq.missing
         << std::setw(14) << r.trailer_seq.out_of_order << "  " << JoinNames(r.channels) << "\n";
    }
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
      os << c.channel << ": " << c.sequence_field << " " << *c.first_sequence << " .. " << *c.last_sequence;
      if (Publishers(c) > 1) os << " (" << Publishers(c) << " publishers, each its own sequence)";
      os << ", " << c.sequence_gaps << " gaps (" << c.missing << " missing), " << c.out_of_order
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
    cj["signed_senders"] = c.signed_senders;
    cj["unsigned_count"] = c.unsigned_count;
    j["channels"].push_back(cj);
  }
  j["senders"] = nlohmann::json::array();
  for (const SenderSummary& r : s.senders) {
    nlohmann::json sj;
    sj["sender"] = SenderHex(r.sender);  // hex: a JSON number cannot hold every uint64
    sj["count"] = r.count;
    sj["channels"] = r.channels;
    sj["first_sequence"] = *r.trailer_seq.first;
    sj["last_sequence"] = *r.trailer_seq.last;
    sj["sequence_gaps"] = r.trailer_seq.gaps;
    sj["missing"] = r.trailer_seq.missing;
    sj["out_of_order"] = r.trailer_seq.out_of_order;
    j["senders"].push_back(sj);
  }
  return j.dump(2) + "\n";
}

}  // namespace minenav
