#pragma once
// Runs log_tool (LOG_TOOL_PATH, a compile definition) through the shell with its output in
// temporary files: the helper of the log_tool command-line tests.

#include <sys/wait.h>

#include <cstdlib>
#include <string>

#include "logger/test_logs.h"

#ifndef LOG_TOOL_PATH
#error "LOG_TOOL_PATH must name the log_tool binary (logger/CMakeLists.txt defines it)"
#endif

namespace minenav::logger_test {

struct RunResult {
  int exit_code = -1;
  std::string out, err;
};

// `s` in single quotes for the shell.
inline std::string Quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// `env`: assignments the shell puts before the command (e.g. "PATH=/nonexistent").
inline RunResult LogTool(const std::string& args, const std::string& env = "") {
  const std::string out = TempPath("stdout.txt"), err = TempPath("stderr.txt");
  const std::string cmd = (env.empty() ? "" : env + " ") + std::string(LOG_TOOL_PATH) + " " + args + " >" +
                          Quote(out) + " 2>" + Quote(err);
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = ReadAll(out);
  r.err = ReadAll(err);
  return r;
}

}  // namespace minenav::logger_test
