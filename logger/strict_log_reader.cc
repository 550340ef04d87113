#include "logger/strict_log_reader.h"

#include <cstring>
#include <filesystem>
#include <system_error>

#include "common/file_io.h"

namespace minenav {

namespace {

constexpr uint32_t kEventMagic = 0xEDA1DA01u;
// Larger than any message we send (a 100 MB contour map would already be absurd).
constexpr int64_t kMaxEventBytes = int64_t{1} << 30;
constexpr int64_t kMaxChannelBytes = 256;  // LCM's own limit is 63

uint64_t BigEndian(const uint8_t* p, int n) {
  uint64_t v = 0;
  for (int i = 0; i < n; ++i) v = (v << 8) | p[i];
  return v;
}

}  // namespace

StrictLogReader::StrictLogReader(const std::string& path) : path_(path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": is a directory, not an LCM log");
  file_ = std::fopen(path.c_str(), "rb");
  if (!file_) throw InputError(path + ": cannot open log for reading");
  if (std::fseek(file_, 0, SEEK_END) == 0) {
    file_size_ = std::ftell(file_);
    std::fseek(file_, 0, SEEK_SET);
  }
}

StrictLogReader::~StrictLogReader() {
  if (file_) std::fclose(file_);
}

bool StrictLogReader::Next(LogRecord* record) {
  uint8_t header[28];
  const size_t got = std::fread(header, 1, sizeof(header), file_);
  const std::string where = path_ + ": event at byte " + std::to_string(position_);
  if (got == 0 && std::feof(file_)) return false;
  if (got != sizeof(header)) {
    if (got >= 4 && BigEndian(header, 4) != kEventMagic)
      throw InputError(where + ": bad magic number, not an LCM event log or corrupt");
    throw InputError(where + ": truncated event header (" + std::to_string(got) + " of 28 bytes)");
  }
  if (BigEndian(header, 4) != kEventMagic)
    throw InputError(where + ": bad magic number, not an LCM event log or corrupt");
  const auto channel_len = static_cast<int32_t>(BigEndian(header + 20, 4));
  const auto data_len = static_cast<int32_t>(BigEndian(header + 24, 4));
  if (channel_len <= 0 || channel_len > kMaxChannelBytes)
    throw InputError(where + ": channel name length " + std::to_string(channel_len) + " is invalid");
  if (data_len < 0 || data_len > kMaxEventBytes)
    throw InputError(where + ": payload length " + std::to_string(data_len) + " is invalid");
  record->eventnum = static_cast<int64_t>(BigEndian(header + 4, 8));
  record->timestamp = static_cast<int64_t>(BigEndian(header + 12, 8));
  record->offset = position_;
  record->channel.resize(static_cast<size_t>(channel_len));
  record->data.resize(static_cast<size_t>(data_len));
  const int64_t need = int64_t{channel_len} + data_len;
  if (position_ + 28 + need > file_size_)
    throw InputError(where + ": truncated event (" + std::to_string(file_size_ - position_ - 28) + " of " +
                     std::to_string(need) + " bytes of channel and payload in the file)");
  if (std::fread(record->channel.data(), 1, record->channel.size(), file_) != record->channel.size() ||
      (data_len > 0 && std::fread(record->data.data(), 1, record->data.size(), file_) != record->data.size()))
    throw InputError(where + ": read error");
  position_ += 28 + need;
  return true;
}

}  // namespace minenav
