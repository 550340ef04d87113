#pragma once
// A strict reader of LCM event logs (the files lcm-logger writes, DESIGN.md "File
// contracts") for the log tools, which must say where a log is damaged.
//
// common/node/event_log.h's LogReader goes through lcm_eventlog, which silently skips
// bytes until it finds the next magic number and stops quietly at a truncated last
// event: right for replay, wrong for inspection. This reader parses the format itself and
// stops with the byte offset at the first damage. Format of one event (big-endian):
//   uint32 magic 0xEDA1DA01, int64 eventnum, int64 timestamp (us),
//   int32 channel length, int32 data length, channel bytes, data bytes.
// Logs are written with common/node/event_log.h's LogWriter.

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace minenav {

struct LogRecord {
  int64_t eventnum = 0;
  int64_t timestamp = 0;  // us, when the logger received it (or when a tool wrote it)
  int64_t offset = 0;     // byte offset of the event in the file
  std::string channel;
  std::vector<uint8_t> data;
};

class StrictLogReader {
 public:
  // Throws InputError if the file cannot be opened.
  explicit StrictLogReader(const std::string& path);
  ~StrictLogReader();
  StrictLogReader(const StrictLogReader&) = delete;
  StrictLogReader& operator=(const StrictLogReader&) = delete;

  // Reads the next event. Returns false at the clean end of the file. Throws InputError
  // (one line: file, byte offset, what) for a bad magic number, a truncated event or
  // absurd lengths.
  bool Next(LogRecord* record);

  const std::string& path() const { return path_; }
  int64_t file_size() const { return file_size_; }
  int64_t position() const { return position_; }

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
  int64_t file_size_ = 0;
  int64_t position_ = 0;
};

}  // namespace minenav
