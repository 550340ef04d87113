#include "logger/strict_log_reader.h"

#include "common/file_io.h"

namespace minenav {

bool StrictLogReader::Next(LogRecord* record) {
  const LogEvent* e = reader_.NextInPlace();
  if (e == nullptr) {
    if (!reader_.truncation().empty()) throw InputError(reader_.truncation());
    return false;
  }
  record->eventnum = e->eventnum;
  record->timestamp = e->timestamp;
  record->offset = e->offset;
  record->channel = e->channel;
  record->data = e->data;
  return true;
}

}  // namespace minenav
