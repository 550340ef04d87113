#pragma once
// Reading and writing LCM event logs (the files lcm-logger writes and lcm-logplayer
// reads). Batch mode (log_bus.h), the log tools and the tests all go through these two
// classes.
//
// The reader parses the format itself instead of using lcm_eventlog, which silently skips
// bytes until the next magic number (a log with garbage in the middle then maps a fraction
// of its scans and "succeeds") and crashes on a header claiming 2 GB of payload. Format of
// one event (big-endian): uint32 magic 0xEDA1DA01, int64 eventnum, int64 timestamp (us),
// int32 channel length, int32 data length, channel bytes, data bytes. Damage in the middle
// of a log is an InputError naming the byte offset; a last event cut short (a logger
// killed mid-write) ends the log, and trailing_bytes() says how much was left.

#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/node/conversions.h"

namespace lcm {
class LogFile;
}

namespace minenav {

// One event of a log, owned.
struct LogEvent {
  int64_t eventnum = 0;
  int64_t timestamp = 0;  // us; receive time for lcm-logger logs, message time for ours
  int64_t offset = 0;     // byte offset of the event in the file
  std::string channel;
  std::vector<uint8_t> data;
};

// Reads events in file order.
//   LogReader reader("run.lcm");
//   while (auto event = reader.Next()) { ... }
class LogReader {
 public:
  // Throws InputError naming the file when it cannot be opened.
  explicit LogReader(const std::string& path);
  ~LogReader();
  LogReader(const LogReader&) = delete;
  LogReader& operator=(const LogReader&) = delete;

  // Largest payload of one event (bytes): more is damage, not data.
  static constexpr int64_t kMaxEventBytes = int64_t{1} << 30;
  // Longest channel name (LCM's own limit is 63).
  static constexpr int64_t kMaxChannelBytes = 256;

  // The next event, or nullopt at the end of the file. Throws InputError (one line: file,
  // byte offset, what) for a bad magic number, an absurd length, or a last event that is
  // cut short while another event starts after it (damage, not a crash of the writer).
  std::optional<LogEvent> Next();
  // Like Next() but without copying the payload: the returned pointer stays valid until
  // the next call. nullptr at the end.
  const LogEvent* NextInPlace();

  int64_t events_read() const { return events_read_; }
  // Bytes after the last complete event (a log cut short by a crash or a full disk).
  // Valid once Next() has returned nullopt.
  int64_t trailing_bytes() const { return trailing_bytes_; }
  // Why the last event was incomplete ("" when the log ended cleanly).
  const std::string& truncation() const { return truncation_; }
  const std::string& path() const { return path_; }
  int64_t file_size() const { return file_size_; }
  int64_t position() const { return position_; }

 private:
  // Records a cut-short last event; throws if the rest of the file holds another event.
  void EndTruncated(const std::string& where, const std::string& what);

  std::string path_;
  std::FILE* file_ = nullptr;
  int64_t file_size_ = 0;
  int64_t position_ = 0;
  int64_t events_read_ = 0;
  int64_t trailing_bytes_ = 0;
  std::string truncation_;
  LogEvent current_;
};

// Writes events. The file is written as PATH.partial and renamed to PATH by Close(), so
// a run that fails part-way never leaves a file claiming to be complete; a writer
// destroyed without Close() removes its partial file.
class LogWriter {
 public:
  // Throws InputError naming the file when it cannot be created.
  explicit LogWriter(const std::string& path);
  ~LogWriter();
  LogWriter(const LogWriter&) = delete;
  LogWriter& operator=(const LogWriter&) = delete;

  // Throws std::runtime_error when the write fails (disk full).
  void Write(const std::string& channel, int64_t timestamp, const void* data, int size);
  // Writes a generated LCM message with the event timestamp = msg.utime.
  template <typename T>
  void Write(const std::string& channel, const T& msg) {
    WriteMessage(channel, msg.utime, msg);
  }
  template <typename T>
  void WriteMessage(const std::string& channel, int64_t timestamp, const T& msg) {
    const std::vector<uint8_t> bytes = EncodeMessage(msg);
    Write(channel, timestamp, bytes.data(), static_cast<int>(bytes.size()));
  }

  void Flush();
  // Flushes, closes and renames PATH.partial to PATH. Throws std::runtime_error on failure.
  void Close();
  // Flushes and closes, leaving the events written under PATH.partial (an interrupted run).
  void CloseAsPartial();

  int64_t events_written() const { return events_written_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_, partial_path_;
  std::unique_ptr<lcm::LogFile> file_;
  int64_t events_written_ = 0;
};

}  // namespace minenav
