#include "common/node/log_bus.h"

#include "common/log.h"

namespace minenav {

LogBus::LogBus(const std::string& input_log, const Clock& clock) : reader_(input_log), clock_(clock) {}

LogBus::~LogBus() = default;

void LogBus::SetOutputLog(const std::string& path) { output_ = std::make_unique<LogWriter>(path); }

bool LogBus::Publish(const std::string& channel, const void* data, int size) {
  const int64_t utime = clock_.NowUtime();
  bool ok = true;
  if (output_ != nullptr) {
    try {
      output_->Write(channel, utime, data, size);
    } catch (const std::exception& e) {
      MINENAV_LOG(kError) << e.what();
      ok = false;
    }
  }
  if (on_publish_) on_publish_(channel, utime, static_cast<const uint8_t*>(data), size);
  CountPublished(ok, channel);
  return ok;
}

void LogBus::Subscribe(const std::string& channel, RawHandler handler) {
  subscriptions_.push_back({ChannelMatcher(channel), std::move(handler)});
}

const LogEvent* LogBus::Fill() {
  if (pending_ == nullptr && !at_end_) {
    pending_ = reader_.NextInPlace();
    if (pending_ == nullptr) {
      at_end_ = true;
      if (reader_.trailing_bytes() > 0) {
        MINENAV_LOG(kWarn) << reader_.truncation() << ": " << reader_.trailing_bytes()
                           << " bytes after the last complete event ignored (log cut short?)";
      }
    }
  }
  return pending_;
}

std::optional<int64_t> LogBus::PeekTimestamp() {
  const LogEvent* e = Fill();
  if (e == nullptr) return std::nullopt;
  return e->timestamp;
}

bool LogBus::DispatchNext() {
  const LogEvent* e = Fill();
  if (e == nullptr) return false;
  RawMessage raw;
  raw.channel = e->channel;
  raw.data = e->data.data();
  raw.size = static_cast<int>(e->data.size());
  raw.utime = e->timestamp;
  for (Subscription& sub : subscriptions_) {
    if (!sub.matcher.Matches(raw.channel)) continue;
    // Same guarantee as live: a handler's exception is a bad message, not a crash.
    try {
      sub.handler(raw);
    } catch (const std::exception& ex) {
      ReportBad(raw.channel, "channel " + e->channel + ": handler failed: " + ex.what());
    }
  }
  ++events_dispatched_;
  pending_ = nullptr;  // the reader reuses its buffer on the next read
  return true;
}

int LogBus::HandleFor(int64_t /*timeout_us*/) { return DispatchNext() ? 1 : 0; }

void LogBus::Close() {
  if (output_ != nullptr) output_->Close();
}

void LogBus::CloseIncomplete() {
  if (output_ == nullptr) return;
  output_->CloseAsPartial();
  MINENAV_LOG(kWarn) << "interrupted: publications so far kept in " << output_->path() << ".partial";
}

}  // namespace minenav
