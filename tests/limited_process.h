#pragma once
// A process of the fleet run by a test under a memory bound, with its peak resident set
// size measured (issue 11: hostile input must not make a process allocate gigabytes).
//
// The bound is RLIMIT_AS, set in the child between fork and exec, and the measurement is
// the peak RSS: VmHWM from /proc/PID/status while the process runs, ru_maxrss (wait4)
// once it is reaped, so memory zero-filled just before a crash still counts. Under
// AddressSanitizer (which reserves terabytes of virtual memory) no RLIMIT_AS is set and
// only the RSS is checked.

#include <sys/types.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tests/sanitizer.h"

namespace minenav::testing {

// RLIMIT_AS for the processes under test: 3 GiB (0 = none under ASan). Not lower: LCM
// 1.3.1 allocates `count` elements before it reads past the buffer, so below ~2.2 GiB a
// 2^29-float scan would end in a caught bad_alloc and hide the out-of-bounds read the
// tests are about. The tight bound is the RSS check (kMaxPeakRssKb).
inline constexpr uint64_t kHostileAddressSpaceLimit = kUnderAddressSanitizer ? 0 : (uint64_t{3} << 30);
// Peak RSS a process may reach while it handles hostile input: 300 MB (700 MB under
// ASan, whose shadow memory and quarantine count as resident). Every hostile payload of
// the tests would make the unfixed code zero-fill at least 1 GiB.
inline constexpr int64_t kMaxPeakRssKb = kUnderAddressSanitizer ? 700 * 1024 : 300 * 1024;
class LimitedProcess {
 public:
  // argv[0] must be a path (no PATH lookup). stdout and stderr go to `output_path`
  // (truncated). `address_space_bytes` = RLIMIT_AS of the child, 0 = none. Throws
  // std::runtime_error when the program cannot be started.
  LimitedProcess(const std::vector<std::string>& argv, const std::string& output_path,
                 uint64_t address_space_bytes = kHostileAddressSpaceLimit);
  // Kills (SIGKILL) and reaps a child still running.
  ~LimitedProcess();
  LimitedProcess(const LimitedProcess&) = delete;
  LimitedProcess& operator=(const LimitedProcess&) = delete;

  pid_t pid() const { return pid_; }
  void Signal(int signal);
  // The exit code (128 + signal number if killed), or nullopt if still running after
  // timeout_s seconds.
  std::optional<int> Wait(double timeout_s);
  bool Running();
  // Peak resident set size in kB so far (VmHWM while running, ru_maxrss once reaped);
  // -1 if unknown.
  int64_t PeakRssKb();
  // CPU time (user + system) the running process used so far, in seconds; -1 if unknown.
  double CpuSeconds() const;
  const std::string& output_path() const { return output_path_; }
  // The last `max_chars` characters of the output file.
  std::string OutputTail(size_t max_chars = 3000) const;

 private:
  pid_t pid_ = -1;
  std::string output_path_;
  std::optional<int> exit_code_;
  int64_t peak_rss_kb_ = -1;
};

struct ProcessResult {
  std::optional<int> exit_code;  // nullopt: still running at the timeout (then killed)
  int64_t peak_rss_kb = -1;
  std::string output;            // stdout and stderr
};

// Runs argv to completion under the bound (killed after timeout_s seconds).
ProcessResult RunLimited(const std::vector<std::string>& argv, const std::string& output_path, double timeout_s,
                         uint64_t address_space_bytes = kHostileAddressSpaceLimit);

// "exit 2", "killed by signal 11 (exit 139)", "still running"...
std::string DescribeExit(const std::optional<int>& exit_code);

}  // namespace minenav::testing
