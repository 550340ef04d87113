// survey_client's node through the fake bus: no request without a pose; a request per
// station from the latest pose; the next only after the tracker's DONE and the dwell; a
// refused path retried, then the station skipped; the process stopped after the last one.

#include "tracker/survey_client_node.h"

#include <gtest/gtest.h>

#include "common/config_testing.h"
#include "common/node/conversions.h"
#include "common/node/fake_runtime.h"
#include "minenav/path_request_t.hpp"
#include "minenav/path_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "minenav/task_status_t.hpp"

namespace minenav {
namespace {

constexpr int64_t kT0 = 1'700'000'000'000'000;

struct Harness {
  explicit Harness(const SurveyClientOptions& o, const std::vector<Station>& stations)
      : node(fake.runtime(), o, stations) {}
  void Tick() {
    clock.Advance(500'000);
    runtime->SpinOnce(0);
  }
  std::vector<path_request_t> Requests() const { return bus->Decoded<path_request_t>("PATH_REQUEST"); }
  void Answer(int64_t id, bool feasible) {
    path_t p{};
    p.utime = clock.NowUtime();
    p.request_id = id;
    p.feasible = feasible;
    p.status = feasible ? "ok" : "no path: walled in";
    bus->InjectMessage("PATH", p);
  }
  void Status(int64_t id, int8_t state) {
    task_status_t s{};
    s.utime = clock.NowUtime();
    s.task_id = id;
    s.state = state;
    s.message = "test";
    bus->InjectMessage("TASK_STATUS", s);
  }
  ManualClock clock{kT0};
  FakeRuntime fake{clock};
  FakeBus* bus = &fake.bus();
  NodeRuntime* runtime = &fake.runtime();
  SurveyClientNode node;
};

TEST(SurveyClientNodeTest, RequestsEachStationAfterTheTrackerIsDone) {
  SurveyClientOptions o;
  o.stations = "test";
  o.requests.dwell = 1.0;
  o.requests.max_attempts = 2;
  o.requests.retry_delay = 0.0;
  Harness h(o, {Station{Pose2(5, 0, 0)}, Station{Pose2(10, 0, 0)}, Station{Pose2(15, 0, 0)}});
  h.Tick();
  h.Tick();
  EXPECT_TRUE(h.Requests().empty()) << "no pose yet";
  PoseEstimate e;
  e.utime = h.clock.NowUtime();
  e.pose = Pose2(1, 2, 0.1);
  e.converged = true;
  h.bus->InjectMessage("POSE", ToLcm(e));
  h.Tick();
  h.Tick();
  ASSERT_EQ(h.Requests().size(), 1u);
  const path_request_t first = h.Requests()[0];
  EXPECT_DOUBLE_EQ(first.start.x, 1.0);
  EXPECT_DOUBLE_EQ(first.goal.x, 5.0);
  EXPECT_FALSE(first.allow_unknown) << "seen free space only, unless asked";
  h.Answer(first.request_id, true);
  for (int k = 0; k < 4; ++k) h.Tick();
  EXPECT_EQ(h.Requests().size(), 1u) << "waiting for the tracker";
  h.Status(first.request_id + 99, task_status_t::DONE);  // not ours
  h.Status(first.request_id, task_status_t::DONE);
  h.Tick();
  h.Tick();  // 0.5 s of the 1 s dwell
  EXPECT_EQ(h.Requests().size(), 1u);
  h.Tick();
  h.Tick();
  ASSERT_EQ(h.Requests().size(), 2u);
  const path_request_t second = h.Requests()[1];
  EXPECT_DOUBLE_EQ(second.goal.x, 10.0);
  EXPECT_NE(second.request_id, first.request_id);
  // No path, twice: skipped; the third station is asked for.
  h.Answer(second.request_id, false);
  h.Tick();
  h.Tick();
  ASSERT_EQ(h.Requests().size(), 3u);
  EXPECT_DOUBLE_EQ(h.Requests()[2].goal.x, 10.0) << "the retry";
  h.Answer(h.Requests()[2].request_id, false);
  h.Tick();
  h.Tick();
  ASSERT_EQ(h.Requests().size(), 4u);
  EXPECT_DOUBLE_EQ(h.Requests()[3].goal.x, 15.0);
  // The tracker fails it twice as well: the tour ends and the process stops.
  EXPECT_FALSE(h.runtime->StopRequested());
  for (int attempt = 0; attempt < 2; ++attempt) {
    const int64_t id = h.Requests().back().request_id;
    h.Answer(id, true);
    h.Status(id, task_status_t::FAILED);
    h.Tick();
    h.Tick();
  }
  EXPECT_TRUE(h.runtime->StopRequested());
}

// A planner that has just refused a goal answers the same at once: the retry waits
// retry_delay (the map and the vehicle may change meanwhile).
TEST(SurveyClientNodeTest, ARetryWaitsItsDelay) {
  SurveyClientOptions o;
  o.stations = "test";
  o.requests.retry_delay = 2.0;
  Harness h(o, {Station{Pose2(5, 0, 0)}});
  PoseEstimate e;
  e.utime = h.clock.NowUtime();
  e.pose = Pose2(1, 2, 0.1);
  e.converged = true;
  h.bus->InjectMessage("POSE", ToLcm(e));
  h.Tick();
  h.Tick();
  ASSERT_EQ(h.Requests().size(), 1u);
  h.Answer(h.Requests()[0].request_id, false);
  h.Tick();  // the answer: a retry due in 2 s
  for (int k = 0; k < 3; ++k) {
    h.Tick();
    EXPECT_EQ(h.Requests().size(), 1u) << "within the delay, tick " << k;
  }
  h.Tick();
  h.Tick();
  EXPECT_EQ(h.Requests().size(), 2u) << "after it";
}

TEST(SurveyClientNodeTest, EveryOptionIsReachable) {
  const auto keys = ExpectEveryOptionReachable<SurveyClientOptions>(
      SurveyClientOptions(), [](ConfigSchema& s, SurveyClientOptions& o) { DeclareOptions(s, o); });
  EXPECT_EQ(keys.size(), 16u);  // stations, 4 channels, rate, 3 request values, reverse, unknown, exit, the 4 requests.*
  EXPECT_THROW(LoadClientStations(SurveyClientOptions()), UsageError);
}

}  // namespace
}  // namespace minenav
