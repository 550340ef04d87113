#include "common/node/event_log.h"

#include <cstdio>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>
#include <system_error>

#include "common/file_io.h"

namespace minenav {

namespace {

constexpr uint32_t kEventMagic = 0xEDA1DA01u;
constexpr int kHeaderBytes = 28;

uint64_t BigEndian(const uint8_t* p, int n) {
  uint64_t v = 0;
  for (int i = 0; i < n; ++i) v = (v << 8) | p[i];
  return v;
}

}  // namespace

LogReader::LogReader(const std::string& path) : path_(path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": is a directory, not an LCM log");
  file_ = std::fopen(path.c_str(), "rb");
  if (file_ == nullptr) throw InputError(path + ": cannot open LCM log for reading");
  const auto size = std::filesystem::file_size(path, ec);
  file_size_ = ec ? 0 : static_cast<int64_t>(size);
}

LogReader::~LogReader() {
  if (file_ != nullptr) std::fclose(file_);
}

void LogReader::EndTruncated(const std::string& where, const std::string& what) {
  // A writer killed mid-event leaves one partial event at the very end. If an event
  // starts anywhere after this one, the length fields are damaged instead.
  std::vector<uint8_t> tail(1 << 16);
  uint32_t window = 0;
  int64_t offset = position_ + 4;
  std::fseek(file_, static_cast<long>(offset), SEEK_SET);
  int64_t index = 0;
  while (true) {
    const size_t got = std::fread(tail.data(), 1, tail.size(), file_);
    if (got == 0) break;
    for (size_t i = 0; i < got; ++i, ++index) {
      window = (window << 8) | tail[i];
      if (index >= 3 && window == kEventMagic)
        throw InputError(where + ": " + what + ", but another event starts at byte " +
                         std::to_string(offset + index - 3) + ": the log is damaged");
    }
  }
  trailing_bytes_ = file_size_ - position_;
  truncation_ = where + ": " + what;
}

const LogEvent* LogReader::NextInPlace() {
  if (!truncation_.empty()) return nullptr;
  uint8_t header[kHeaderBytes];
  const size_t got = std::fread(header, 1, sizeof(header), file_);
  const std::string where = path_ + ": event at byte " + std::to_string(position_);
  if (got == 0) return nullptr;  // the clean end
  if (got >= 4 && BigEndian(header, 4) != kEventMagic)
    throw InputError(where + ": bad magic number, not an LCM event log or corrupt");
  if (got != sizeof(header)) {
    EndTruncated(where, "truncated event header (" + std::to_string(got) + " of 28 bytes)");
    return nullptr;
  }
  const auto channel_len = static_cast<int32_t>(BigEndian(header + 20, 4));
  const auto data_len = static_cast<int32_t>(BigEndian(header + 24, 4));
  if (channel_len <= 0 || channel_len > kMaxChannelBytes)
    throw InputError(where + ": channel name length " + std::to_string(channel_len) + " is invalid");
  if (data_len < 0 || data_len > kMaxEventBytes)
    throw InputError(where + ": payload length " + std::to_string(data_len) + " is invalid");
  const int64_t need = int64_t{channel_len} + data_len;
  if (position_ + kHeaderBytes + need > file_size_) {
    EndTruncated(where, "truncated event (" + std::to_string(file_size_ - position_ - kHeaderBytes) + " of " +
                            std::to_string(need) + " bytes of channel and payload in the file)");
    return nullptr;
  }
  current_.eventnum = static_cast<int64_t>(BigEndian(header + 4, 8));
  current_.timestamp = static_cast<int64_t>(BigEndian(header + 12, 8));
  current_.offset = position_;
  current_.channel.resize(static_cast<size_t>(channel_len));
  current_.data.resize(static_cast<size_t>(data_len));
  if (std::fread(current_.channel.data(), 1, current_.channel.size(), file_) != current_.channel.size() ||
      (data_len > 0 && std::fread(current_.data.data(), 1, current_.data.size(), file_) != current_.data.size()))
    throw InputError(where + ": read error");
  position_ += kHeaderBytes + need;
  ++events_read_;
  return &current_;
}

std::optional<LogEvent> LogReader::Next() {
  const LogEvent* e = NextInPlace();
  if (e == nullptr) return std::nullopt;
  return *e;
}

LogWriter::LogWriter(const std::string& path) : path_(path), partial_path_(path + ".partial") {
  file_ = std::make_unique<lcm::LogFile>(partial_path_, "w");
  if (!file_->good()) throw InputError(path + ": cannot create LCM log for writing");
}

LogWriter::~LogWriter() {
  if (file_ != nullptr) {
    file_.reset();
    std::error_code ec;
    std::filesystem::remove(partial_path_, ec);
  }
}

void LogWriter::Write(const std::string& channel, int64_t timestamp, const void* data, int size) {
  if (file_ == nullptr) throw std::runtime_error(path_ + ": write after Close()");
  lcm::LogEvent event{};
  event.timestamp = timestamp;
  event.channel = channel;
  event.datalen = size;
  event.data = const_cast<void*>(data);
  if (file_->writeEvent(&event) != 0) throw std::runtime_error(path_ + ": cannot write event (disk full?)");
  ++events_written_;
}

void LogWriter::Flush() {
  if (file_ != nullptr) std::fflush(file_->getFilePtr());
}

void LogWriter::CloseAsPartial() {
  if (file_ == nullptr) return;
  std::fflush(file_->getFilePtr());
  file_.reset();
}

void LogWriter::Close() {
  if (file_ == nullptr) return;
  FILE* f = file_->getFilePtr();
  const bool ok = std::fflush(f) == 0 && std::ferror(f) == 0;
  file_.reset();
  if (!ok) {
    std::error_code ec;
    std::filesystem::remove(partial_path_, ec);
    throw std::runtime_error(path_ + ": cannot write log (disk full?)");
  }
  std::error_code ec;
  std::filesystem::rename(partial_path_, path_, ec);
  if (ec) throw std::runtime_error(path_ + ": cannot rename " + partial_path_ + ": " + ec.message());
}

}  // namespace minenav
