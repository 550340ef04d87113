#include "fleet/restart_policy.h"

#include <algorithm>
#include <csignal>
#include <cmath>
#include <cstring>

#include "fleet/number_text.h"

namespace minenav {

namespace {

int64_t SecondsToUs(double s) { return static_cast<int64_t>(std::llround(s * 1e6)); }

std::string FormatSeconds(double s) { return NumberText(s) + " s"; }

}  // namespace

void DeclareOptions(OptionScope scope, RestartOptions& options) {
  scope.AddDouble("backoff_initial", &options.backoff_initial, "s",
                  "delay before the first restart; it doubles with each failure in a row", 0.0, 3600.0);
  scope.AddDouble("backoff_max", &options.backoff_max, "s", "longest delay before a restart", 0.0, 3600.0);
  scope.AddDouble("stable_after", &options.stable_after, "s",
                  "a run at least this long makes its failure the first in a row again", 0.0, 86400.0);
  scope.AddInt("crash_loop_failures", &options.crash_loop_failures,
               "failures within crash_loop_window that make a crash loop: the process is given up", 1, 1000);
  scope.AddDouble("crash_loop_window", &options.crash_loop_window, "s", "window of the crash-loop count", 0.001,
                  86400.0);
}

void Validate(const RestartOptions& options) {
  if (options.backoff_max < options.backoff_initial)
    throw UsageError("restart.backoff_max (" + FormatSeconds(options.backoff_max) +
                     ") is below restart.backoff_initial (" + FormatSeconds(options.backoff_initial) + ")");
}

std::string Describe(const ExitStatus& status) {
  if (status.signal == 0) return "exit code " + std::to_string(status.code);
  const char* abbrev = sigabbrev_np(status.signal);
  return std::string("killed by ") + (abbrev != nullptr ? std::string("SIG") + abbrev : "signal " + std::to_string(status.signal));
}

int64_t BackoffDelayUs(const RestartOptions& options, int consecutive_failures) {
  const int doublings = std::max(0, std::min(consecutive_failures - 1, 62));
  const double delay = std::min(options.backoff_max, options.backoff_initial * std::ldexp(1.0, doublings));
  return SecondsToUs(delay);
}

bool RestartsAfter(RestartPolicy policy, bool failed) {
  switch (policy) {
    case RestartPolicy::kNever: return false;
    case RestartPolicy::kOnFailure: return failed;
    case RestartPolicy::kAlways: return true;
  }
  return false;
}

void FailureHistory::Add(const RestartOptions& options, int64_t started, int64_t now) {
  if (now - started >= SecondsToUs(options.stable_after)) in_a_row_ = 0;
  ++in_a_row_;
  times_.push_back(now);
  // Only the window matters; keep the deque short.
  while (!times_.empty() && now - times_.front() > SecondsToUs(options.crash_loop_window)) times_.pop_front();
}

int FailureHistory::WithinWindow(const RestartOptions& options, int64_t now) const {
  int n = 0;
  for (const int64_t t : times_)
    if (now - t <= SecondsToUs(options.crash_loop_window)) ++n;
  return n;
}

AfterExit DecideAfterExit(RestartPolicy policy, const RestartOptions& options, FailureHistory& history,
                          int64_t started, int64_t now, bool failed, const std::string& what) {
  AfterExit after;
  if (!RestartsAfter(policy, failed)) {
    after.kind = AfterExit::Kind::kEnded;
    after.reason = what;
    return after;
  }
  history.Add(options, started, now);
  if (history.CrashLoop(options, now)) {
    after.kind = AfterExit::Kind::kGiveUp;
    after.reason = "crash loop: " + std::to_string(history.WithinWindow(options, now)) + " failures within " +
                   FormatSeconds(options.crash_loop_window) + " (last: " + what + ")";
    return after;
  }
  after.kind = AfterExit::Kind::kRestart;
  const int64_t delay = BackoffDelayUs(options, history.in_a_row());
  after.restart_at = now + delay;
  after.reason = what + ": restarting in " + NumberText(static_cast<double>(delay) * 1e-6) + " s (failure " +
                 std::to_string(history.in_a_row()) + " in a row)";
  return after;
}

}  // namespace minenav
