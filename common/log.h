#pragma once
// One-line log messages on stderr: "[program] LEVEL message". Thread-safe (one write
// per line).  Usage: MINENAV_LOG(kWarn) << "scan " << id << " skipped: " << reason;

#include <sstream>
#include <string>

namespace minenav {

enum class LogLevel { kDebug = 0, kInfo = 1, kWarn = 2, kError = 3 };

void SetLogProgramName(const std::string& name);
void SetLogLevel(LogLevel level);
LogLevel GetLogLevel();
// Parses "debug", "info", "warn", "error"; throws InputError otherwise.
LogLevel ParseLogLevel(const std::string& text);

class LogLine {
 public:
  explicit LogLine(LogLevel level) : level_(level) {}
  ~LogLine();
  LogLine(const LogLine&) = delete;
  LogLine& operator=(const LogLine&) = delete;
  template <typename T>
  LogLine& operator<<(const T& v) {
    if (level_ >= GetLogLevel()) stream_ << v;
    return *this;
  }

 private:
  LogLevel level_;
  std::ostringstream stream_;
};

}  // namespace minenav

#define MINENAV_LOG(level) ::minenav::LogLine(::minenav::LogLevel::level)
