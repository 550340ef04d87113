#include "fleet/restart_policy.h"

#include <gtest/gtest.h>

#include <csignal>

namespace minenav {
namespace {

constexpr int64_t kS = 1'000'000;  // one second in µs

TEST(RestartPolicy, BackoffDoublesFromTheFirstDelayUpToTheCap) {
  RestartOptions o;
  o.backoff_initial = 0.5;
  o.backoff_max = 30.0;
  // 0.5 * 2^(n-1): 0.5, 1, 2, 4, 8, 16, then 32 capped at 30.
  const std::vector<int64_t> expected = {500'000, 1'000'000, 2'000'000, 4'000'000, 8'000'000, 16'000'000, 30'000'000,
                                         30'000'000};
  for (int n = 1; n <= 8; ++n) EXPECT_EQ(BackoffDelayUs(o, n), expected[n - 1]) << n;
  EXPECT_EQ(BackoffDelayUs(o, 1000), 30'000'000) << "no overflow far out";
}

TEST(RestartPolicy, WhichExitsArePolicyRestarts) {
  EXPECT_FALSE(RestartsAfter(RestartPolicy::kNever, true));
  EXPECT_FALSE(RestartsAfter(RestartPolicy::kOnFailure, false));
  EXPECT_TRUE(RestartsAfter(RestartPolicy::kOnFailure, true));
  EXPECT_TRUE(RestartsAfter(RestartPolicy::kAlways, false));
  EXPECT_EQ(Describe(ExitStatus{1, 0}), "exit code 1");
  EXPECT_EQ(Describe(ExitStatus{0, SIGKILL}), "killed by SIGKILL");
  EXPECT_TRUE(ExitStatus{}.success());
  EXPECT_FALSE((ExitStatus{0, SIGSEGV}).success());
}

TEST(RestartPolicy, ACrashLoopIsNFailuresWithinTheWindow) {
  RestartOptions o;
  o.backoff_initial = 1.0;
  o.backoff_max = 4.0;
  o.crash_loop_failures = 4;
  o.crash_loop_window = 20.0;
  FailureHistory h;
  int64_t now = 0;
  // A process that dies 0.1 s after each start: restarts after 1, 2, 4 s, then the 4th
  // failure (at 7.4 s, within 20 s of the first) is a crash loop.
  std::vector<int64_t> delays;
  for (int k = 0; k < 3; ++k) {
    const int64_t started = now;
    now += kS / 10;
    const AfterExit a = DecideAfterExit(RestartPolicy::kOnFailure, o, h, started, now, true, "exit code 1");
    ASSERT_EQ(a.kind, AfterExit::Kind::kRestart) << k;
    delays.push_back(a.restart_at - now);
    now = a.restart_at;
  }
  EXPECT_EQ(delays, (std::vector<int64_t>{1 * kS, 2 * kS, 4 * kS}));
  const AfterExit last = DecideAfterExit(RestartPolicy::kOnFailure, o, h, now, now + kS / 10, true, "exit code 1");
  EXPECT_EQ(last.kind, AfterExit::Kind::kGiveUp);
  EXPECT_EQ(last.reason, "crash loop: 4 failures within 20 s (last: exit code 1)");
}

TEST(RestartPolicy, FailuresSpreadOverMoreThanTheWindowAreNoCrashLoop) {
  RestartOptions o;
  o.backoff_initial = 0.5;
  o.stable_after = 10.0;
  o.crash_loop_failures = 3;
  o.crash_loop_window = 60.0;
  FailureHistory h;
  // A failure every 40 s, each after a run of 40 s: never 3 within 60 s, and each run was
  // stable, so each restart waits only the first delay.
  int64_t now = 0;
  for (int k = 0; k < 10; ++k) {
    const int64_t started = now;
    now += 40 * kS;
    const AfterExit a = DecideAfterExit(RestartPolicy::kAlways, o, h, started, now, false, "exit code 0");
    ASSERT_EQ(a.kind, AfterExit::Kind::kRestart) << k;
    EXPECT_EQ(a.restart_at - now, kS / 2) << k;
    EXPECT_EQ(h.in_a_row(), 1);
    EXPECT_LE(h.WithinWindow(o, now), 2);
  }
}

TEST(RestartPolicy, AStableRunResetsTheBackoffButNotTheCrashLoopCount) {
  RestartOptions o;
  o.backoff_initial = 1.0;
  o.stable_after = 5.0;
  o.crash_loop_failures = 10;
  FailureHistory h;
  h.Add(o, 0, kS / 10);
  h.Add(o, kS, kS + kS / 10);
  EXPECT_EQ(h.in_a_row(), 2);
  EXPECT_EQ(BackoffDelayUs(o, h.in_a_row()), 2 * kS);
  h.Add(o, 2 * kS, 8 * kS);  // ran 6 s >= stable_after
  EXPECT_EQ(h.in_a_row(), 1);
  EXPECT_EQ(h.WithinWindow(o, 8 * kS), 3);
}

TEST(RestartPolicy, EndedExitsAreNotRecorded) {
  RestartOptions o;
  FailureHistory h;
  const AfterExit ok = DecideAfterExit(RestartPolicy::kOnFailure, o, h, 0, kS, false, "exit code 0");
  EXPECT_EQ(ok.kind, AfterExit::Kind::kEnded);
  const AfterExit never = DecideAfterExit(RestartPolicy::kNever, o, h, 0, kS, true, "exit code 2");
  EXPECT_EQ(never.kind, AfterExit::Kind::kEnded);
  EXPECT_EQ(never.reason, "exit code 2");
  EXPECT_EQ(h.WithinWindow(o, kS), 0);
}

TEST(RestartPolicy, OptionsThatContradictEachOtherAreRefused) {
  RestartOptions o;
  o.backoff_initial = 10;
  o.backoff_max = 5;
  EXPECT_THROW(Validate(o), UsageError);
}

}  // namespace
}  // namespace minenav
