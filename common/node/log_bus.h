#pragma once
// Batch mode: a bus whose input is an LCM event log (DESIGN.md: every process runs over
// a log with --log FILE, as fast as it can, deterministically). Events are dispatched
// to the subscribers of their channel in file order; nothing is dropped (unlike
// lcm-logplayer over UDP). Publications go to an optional output log and/or a callback,
// stamped with the batch clock, so a batch run's outputs can be inspected.
// A process does not receive its own publications in batch mode.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/clock.h"
#include "common/node/bus.h"
#include "common/node/event_log.h"

namespace minenav {

class LogBus final : public Bus {
 public:
  // Throws InputError naming the file when the log cannot be opened. `clock` stamps
  // publications (the runtime's ManualClock); it must outlive the bus.
  LogBus(const std::string& input_log, const Clock& clock);
  ~LogBus() override;

  // Publications also go to `path` (an LCM log; written as PATH.partial until Close()).
  void SetOutputLog(const std::string& path);
  using PublishCallback = std::function<void(const std::string& channel, int64_t utime,
                                             const uint8_t* data, int size)>;
  void SetPublishCallback(PublishCallback callback) { on_publish_ = std::move(callback); }

  bool Publish(const std::string& channel, const void* data, int size) override;
  void Subscribe(const std::string& channel, RawHandler handler) override;
  // Dispatches the next event (the timeout is ignored: a log never makes us wait).
  // Returns 1, or 0 at the end of the log.
  int HandleFor(int64_t timeout_us) override;

  // The timestamp of the next event without dispatching it; nullopt at the end.
  std::optional<int64_t> PeekTimestamp();
  // Dispatches the event PeekTimestamp() looked at (or the next one). False at the end.
  bool DispatchNext();

  // Closes the output log (renaming it into place). Call once the run succeeded.
  void Close();
  // Closes the output log and leaves it as PATH.partial (the run was interrupted): what
  // was published is kept, under a name that says it is not complete.
  void CloseIncomplete();

  int64_t events_read() const { return reader_.events_read(); }
  int64_t events_dispatched() const { return events_dispatched_; }
  const LogReader& reader() const { return reader_; }

 private:
  struct Subscription {
    ChannelMatcher matcher;
    RawHandler handler;
  };
  const LogEvent* Fill();

  LogReader reader_;
  const Clock& clock_;
  std::unique_ptr<LogWriter> output_;
  PublishCallback on_publish_;
  std::vector<Subscription> subscriptions_;
  const LogEvent* pending_ = nullptr;
  bool at_end_ = false;
  int64_t events_dispatched_ = 0;
};

}  // namespace minenav
