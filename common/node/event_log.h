#pragma once
// Reading and writing LCM event logs (the files lcm-logger writes and lcm-logplayer
// reads) through LCM's own event-log API, lcm::LogFile. Batch mode (log_bus.h), the
// log tools and the tests all go through these two classes.

#include <cstdint>
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

  // The next event, or nullopt at the end of the file.
  std::optional<LogEvent> Next();
  // Like Next() but without copying the payload: the returned pointer stays valid until
  // the next call. nullptr at the end.
  const LogEvent* NextInPlace();

  int64_t events_read() const { return events_read_; }
  // Bytes after the last complete event (a log cut short by a crash or a full disk).
  // Valid once Next() has returned nullopt.
  int64_t trailing_bytes() const { return trailing_bytes_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::unique_ptr<lcm::LogFile> file_;
  int64_t file_size_ = 0;
  int64_t events_read_ = 0;
  int64_t trailing_bytes_ = 0;
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

  int64_t events_written() const { return events_written_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_, partial_path_;
  std::unique_ptr<lcm::LogFile> file_;
  int64_t events_written_ = 0;
};

}  // namespace minenav
