#pragma once
// Starting a fleet process for the supervisor (fleet/README.md, "Supervision"): its stderr
// (and stdout when asked) appended to its log file, stdin from /dev/null, in a process group
// of its own (a Ctrl-C at the terminal reaches the supervisor only, which then stops each
// process once, cleanly), and SIGTERM to it should the supervisor die without stopping it.
// Test harnesses use tests/child_process.h instead: a file truncated per run, no groups.

#include <sys/types.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "fleet/restart_policy.h"

namespace minenav {

// The path of `program`: as it is when it has a '/', else looked up on $PATH. Throws
// InputError ("... not found" / "... not executable") naming `where`.
std::string ResolveProgram(const std::string& program, const std::string& where);

struct LaunchRequest {
  std::vector<std::string> argv;          // argv[0]: a path (ResolveProgram)
  std::map<std::string, std::string> env;  // added to (or replacing in) the supervisor's environment
  std::string log_path;                   // stderr is appended here
  bool stdout_to_log = false;             // stdout too (else the supervisor's stdout)
};

// Forks and execs. Returns the child's pid (also its process group). Throws
// std::runtime_error when the log cannot be opened or fork fails; a failing exec shows as
// exit code 127 with the reason in the log. The supervisor's own systemd variables
// (NOTIFY_SOCKET, WATCHDOG_*) are not passed on.
pid_t LaunchProcess(const LaunchRequest& request);

// Signals the child's whole process group (a wrapper script and what it started).
void SignalProcessGroup(pid_t pid, int signal);

// The exit of `pid` if it ended (reaped), nullopt while it runs.
std::optional<ExitStatus> PollExit(pid_t pid);

}  // namespace minenav
