#pragma once
// The log tools' reader of LCM event logs: common/node/event_log.h's LogReader (the one
// parser of the format), with a last event cut short reported as damage too, because the
// tools must say where a log is damaged (LogReader ends a replay quietly there).

#include <cstdint>
#include <string>
#include <vector>

#include "common/node/event_log.h"

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
  explicit StrictLogReader(const std::string& path) : reader_(path) {}

  // Reads the next event. Returns false at the clean end of the file. Throws InputError
  // (one line: file, byte offset, what) for a bad magic number, a truncated event or
  // absurd lengths.
  bool Next(LogRecord* record);

  const std::string& path() const { return reader_.path(); }
  int64_t file_size() const { return reader_.file_size(); }
  int64_t position() const { return reader_.position(); }

 private:
  LogReader reader_;
};

}  // namespace minenav
