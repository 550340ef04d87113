#pragma once
// What the supervisor does when a process exits: restart it after an exponentially growing
// delay, or give up on a crash loop (N failures within T seconds), or leave it ended
// (fleet/README.md, "Restarts"). Pure: times are microseconds handed in by the caller.
//
// The same numbers are what systemd is given for a vehicle (`fleet units`): RestartSec=
// is the first delay, StartLimitBurst= / StartLimitIntervalSec= the crash loop.

#include <cstdint>
#include <deque>
#include <string>

#include "common/config.h"
#include "fleet/fleet_file.h"

namespace minenav {

struct RestartOptions {
  double backoff_initial = 0.5;  // s before the first restart; doubles with each failure in a row
  double backoff_max = 30.0;     // s: the delay stops growing here
  double stable_after = 10.0;    // s a process must run for its next failure to count as the first again
  int crash_loop_failures = 5;   // failures within crash_loop_window that make a crash loop: given up
  double crash_loop_window = 60.0;  // s
};
void DeclareOptions(OptionScope scope, RestartOptions& options);
// Throws UsageError for options that contradict each other (backoff_max < backoff_initial).
void Validate(const RestartOptions& options);

// How a process ended: an exit code, or the signal that killed it.
struct ExitStatus {
  int code = 0;    // when signal == 0
  int signal = 0;  // killed by this signal (0: it exited)
  bool success() const { return signal == 0 && code == 0; }
};
std::string Describe(const ExitStatus& status);  // "exit code 1", "killed by SIGKILL"

// The delay before restart number `consecutive_failures` (1 = the first in a row):
// backoff_initial * 2^(n-1), at most backoff_max, in microseconds.
int64_t BackoffDelayUs(const RestartOptions& options, int consecutive_failures);

// Whether the policy restarts a process after an exit (never: no; on-failure: after a
// failure; always: yes). A failure is an exit code other than 0, a signal, or a stop the
// supervisor made because the process was not ready in time.
bool RestartsAfter(RestartPolicy policy, bool failed);

// The failures of one process: how many in a row (for the backoff) and when (for the
// crash loop).
class FailureHistory {
 public:
  // Records a failure at `now` of a run that started at `started`: a run of at least
  // stable_after resets the count in a row first.
  void Add(const RestartOptions& options, int64_t started, int64_t now);
  int in_a_row() const { return in_a_row_; }
  // Failures within the crash-loop window ending at `now`.
  int WithinWindow(const RestartOptions& options, int64_t now) const;
  bool CrashLoop(const RestartOptions& options, int64_t now) const {
    return WithinWindow(options, now) >= options.crash_loop_failures;
  }

 private:
  int in_a_row_ = 0;
  std::deque<int64_t> times_;
};

// What follows an exit that the supervisor did not ask for.
struct AfterExit {
  enum class Kind { kRestart, kGiveUp, kEnded };
  Kind kind = Kind::kEnded;
  int64_t restart_at = 0;  // kRestart: when
  std::string reason;      // one line: why (for the log and the status table)
};
// Records the exit in `history` when the policy restarts after it, and decides. `what`
// says how it ended ("exit code 1"), for the reason.
AfterExit DecideAfterExit(RestartPolicy policy, const RestartOptions& options, FailureHistory& history,
                          int64_t started, int64_t now, bool failed, const std::string& what);

}  // namespace minenav
