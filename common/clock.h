#pragma once
// Time as algorithms and nodes see it, in microseconds since the Unix epoch. Live nodes
// use the wall clock; batch runs over a log use the time of the last message read, so a
// batch run is deterministic and as fast as the CPU allows.

#include <chrono>
#include <cstdint>

namespace minenav {

class Clock {
 public:
  virtual ~Clock() = default;
  virtual int64_t NowUtime() const = 0;
};

class WallClock final : public Clock {
 public:
  int64_t NowUtime() const override {
    return std::chrono::duration_cast<std::chrono::microseconds>(
               std::chrono::system_clock::now().time_since_epoch())
        .count();
  }
};

// Advanced by hand (batch mode: to each message's utime; tests: to whatever they like).
class ManualClock final : public Clock {
 public:
  explicit ManualClock(int64_t utime = 0) : utime_(utime) {}
  int64_t NowUtime() const override { return utime_; }
  void Set(int64_t utime) { utime_ = utime; }
  void Advance(int64_t dt_us) { utime_ += dt_us; }

 private:
  int64_t utime_;
};

}  // namespace minenav
