#pragma once
// What `log_tool info` reports about an LCM event log: per channel the message type,
// count, bytes, rate, first and last time, decode errors and gaps in the sequence
// numbers (seq, or scan_id for scans), which is how dropped messages show up.
//
// A channel may have several publishers (DRIVE_COMMAND: the tracker and, in a cut, the
// cutter), each numbering its own messages: a signed message's sequence is followed per
// sender (the authentication trailer's sender id, common/message_auth.h), an unsigned one's
// per channel. And every signed sender numbers all its signed messages in one more sequence,
// the trailer's: followed per sender across channels, it finds a lost command on any signed
// channel, even one whose seq field is not a per-channel counter (CUT_TASK's is the
// coordinator's task id). The trailers are read, not verified (no keys here): a forger shows
// as a sender of its own.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace minenav {

// Gaps in one sequence of numbers, in the order they came.
struct SequenceGaps {
  std::optional<int64_t> first, last;
  int64_t gaps = 0;          // times the sequence jumped forward by more than one
  int64_t missing = 0;       // numbers those jumps skipped
  int64_t out_of_order = 0;  // times it went backwards or repeated

  void Add(int64_t n);
};

struct ChannelSummary {
  std::string channel;
  std::string type;        // "minenav.ladar_scan_t", "" when foreign
  int64_t count = 0;
  int64_t bytes = 0;       // payload bytes
  int64_t first_timestamp = 0;  // us, log (receive) time
  int64_t last_timestamp = 0;
  double rate_hz = 0.0;    // (count - 1) / (last - first); 0 with fewer than two messages
  std::optional<int64_t> first_utime, last_utime;  // message utime, if the type has one

  int64_t decode_errors = 0;
  std::string first_error;  // one line, with the byte offset of the event

  std::string sequence_field;  // "seq", "scan_id" or "" when the type has none
  std::optional<int64_t> first_sequence, last_sequence;  // of the channel's first and last message
  // Summed over the channel's publishers (one per signing sender, one for the unsigned).
  int64_t sequence_gaps = 0;     // times a sequence jumped forward by more than one
  int64_t missing = 0;           // messages those jumps skipped
  int64_t out_of_order = 0;      // times one went backwards or repeated
  int64_t signed_senders = 0;    // distinct trailer senders among the channel's messages
  int64_t unsigned_count = 0;    // messages without a trailer
};

// One signing sender (a process's random id in the trailer): its signed messages on every
// channel, and the trailer's sequence across them.
struct SenderSummary {
  uint64_t sender = 0;
  int64_t count = 0;
  std::vector<std::string> channels;  // sorted
  SequenceGaps trailer_seq;
};

struct LogSummary {
  std::string path;
  int64_t file_bytes = 0;
  int64_t events = 0;
  int64_t first_timestamp = 0, last_timestamp = 0;  // us
  std::vector<ChannelSummary> channels;             // sorted by name
  std::vector<SenderSummary> senders;               // signing senders, by first appearance
  // Set when the file itself is damaged (bad magic, truncated last event): the summary
  // covers the events before it.
  std::string file_error;

  int64_t total_decode_errors() const;
};

// Reads the whole log. Throws InputError only if the file cannot be opened; damage and
// decode errors are reported in the summary.
LogSummary SummarizeLog(const std::string& path);

std::string FormatLogSummary(const LogSummary& summary);
std::string LogSummaryToJson(const LogSummary& summary);

}  // namespace minenav
