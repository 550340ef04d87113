#include "common/log.h"

#include <unistd.h>

#include <atomic>
#include <mutex>

#include "common/file_io.h"

namespace minenav {

namespace {
std::mutex g_mutex;
std::string g_program = "minenav";
std::atomic<int> g_level{static_cast<int>(LogLevel::kInfo)};
const char* LevelName(LogLevel l) {
  switch (l) {
    case LogLevel::kDebug: return "debug";
    case LogLevel::kInfo: return "info";
    case LogLevel::kWarn: return "warning";
    case LogLevel::kError: return "error";
  }
  return "?";
}
}  // namespace

void SetLogProgramName(const std::string& name) {
  std::lock_guard<std::mutex> lock(g_mutex);
  g_program = name;
}
void SetLogLevel(LogLevel level) { g_level = static_cast<int>(level); }
LogLevel GetLogLevel() { return static_cast<LogLevel>(g_level.load()); }

LogLevel ParseLogLevel(const std::string& text) {
  if (text == "debug") return LogLevel::kDebug;
  if (text == "info") return LogLevel::kInfo;
  if (text == "warn" || text == "warning") return LogLevel::kWarn;
  if (text == "error") return LogLevel::kError;
  throw InputError("log level '" + text + "' is not one of debug, info, warn, error");
}

LogLine::~LogLine() {
  if (level_ < GetLogLevel()) return;
  std::string line;
  {
    std::lock_guard<std::mutex> lock(g_mutex);
    line = "[" + g_program + "] " + LevelName(level_) + ": " + stream_.str() + "\n";
  }
  const ssize_t ignored = ::write(STDERR_FILENO, line.data(), line.size());
  (void)ignored;
}

}  // namespace minenav
