#include "common/node/event_log.h"

#include <cstdio>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>
#include <system_error>

#include "common/file_io.h"

namespace minenav {

LogReader::LogReader(const std::string& path) : path_(path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": is a directory, not an LCM log");
  file_ = std::make_unique<lcm::LogFile>(path, "r");
  if (!file_->good()) throw InputError(path + ": cannot open LCM log for reading");
  const auto size = std::filesystem::file_size(path, ec);
  file_size_ = ec ? 0 : static_cast<int64_t>(size);
  trailing_bytes_ = file_size_;
}

LogReader::~LogReader() = default;

const LogEvent* LogReader::NextInPlace() {
  const lcm::LogEvent* e = file_->readNextEvent();
  if (e == nullptr) return nullptr;
  ++events_read_;
  current_.eventnum = e->eventnum;
  current_.timestamp = e->timestamp;
  current_.channel = e->channel;
  const auto* bytes = static_cast<const uint8_t*>(e->data);
  current_.data.assign(bytes, bytes + (e->datalen > 0 ? e->datalen : 0));
  const long end = std::ftell(file_->getFilePtr());
  if (end >= 0) trailing_bytes_ = file_size_ > end ? file_size_ - end : 0;
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
