#pragma once
// Starting and stopping a program and waiting for it: posix_spawn with the output going to
// a file, signals, and waits with a timeout. The destructor kills and reaps a child that is
// still running, so a failing caller never leaves processes behind. What the tests use to run
// the fleet's processes and what log_tool uses to run rsvg-convert (the fleet's supervisor
// has its own launcher, fleet/child_launcher.h: process groups, logs appended, restarts).

#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

namespace minenav {

class ChildProcess {
 public:
  // argv[0] is looked up on PATH when it has no '/'. stdout and stderr go to
  // `output_path` (truncated) or are inherited when it is empty. Throws std::runtime_error
  // when the program cannot be started.
  explicit ChildProcess(const std::vector<std::string>& argv, const std::string& output_path = "");
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  void Signal(int signal);
  // The exit code (128 + signal number if killed), or nullopt if still running after
  // timeout_s seconds.
  std::optional<int> Wait(double timeout_s);
  bool Running();

 private:
  pid_t pid_ = -1;
  std::optional<int> exit_code_;
};

// A program run to its end: its exit code (-1 when it outlived the timeout and was killed)
// and everything it printed.
struct ProgramRun {
  int exit_code = -1;
  std::string output;
};
// Runs `program` with `args`, its stdout and stderr into `output_path`, for at most
// timeout_s seconds.
ProgramRun RunProgram(const std::string& program, const std::vector<std::string>& args,
                      const std::string& output_path, double timeout_s);

}  // namespace minenav
