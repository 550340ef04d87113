#pragma once
// Runs log_tool (LOG_TOOL_PATH, a compile definition) through the shell with its output in
// temporary files: the helper of carmen_cli_test.cc and carmen_cli_real_test.cc.

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

inline RunResult LogTool(const std::string& args) {
  const std::string out = TempPath("stdout.txt"), err = TempPath("stderr.txt");
  const std::string cmd = std::string(LOG_TOOL_PATH) + " " + args + " >'" + out + "' 2>'" + err + "'";
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = ReadAll(out);
  r.err = ReadAll(err);
  return r;
}

}  // namespace minenav::logger_test
