// The coordinator's node on the fake bus: the mission's messages go out on the right channels
// in the right form (the planner's PATH forwarded on DRIVE_PATH unchanged, cuts on CUT_TASK with
// their face, STOP on DRIVE_COMMAND), the operator's commands are obeyed, hostile messages are
// counted and change nothing, MISSION_STATUS carries the task tree, and the report is written.

#include "coordinator/coordinator_node.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "common/config_testing.h"
#include "common/file_io.h"
#include "common/node/conversions.h"
#include "common/node/fake_runtime.h"
#include "minenav/coordinator_command_t.hpp"
#include "minenav/cutter_command_t.hpp"
#include "minenav/drive_command_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/mission_status_t.hpp"
#include "minenav/path_request_t.hpp"
#include "minenav/path_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "minenav/task_plan_t.hpp"
#include "minenav/task_request_t.hpp"
#include "minenav/task_status_t.hpp"
#include "planner/task_plan_message.h"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

constexpr int64_t kT0 = 1'700'000'000'000'000;

CoordinatorNodeOptions Options() {
  CoordinatorNodeOptions o;
  o.mission.required = "contour_mapper,path_tracker";
  o.mission.face = "40,3,0";
  o.mission.explore = true;
  o.mission.station_dwell = 0.5;
  return o;
}

struct Harness {
  explicit Harness(CoordinatorNodeOptions o) : node(fake.runtime(), std::move(o)) {}
  void Tick(int n = 1) {
    for (int i = 0; i < n; ++i) {
      clock.Advance(100'000);
      Beats();
      runtime->SpinOnce(0);
    }
  }
  void Beats() {
    if ((clock.NowUtime() - kT0) % 1'000'000 != 0) return;
    for (const char* p : {"contour_mapper", "path_tracker"}) {
      heartbeat_t hb{};
      hb.utime = clock.NowUtime();
      hb.process = p;
      hb.state = heartbeat_t::OK;
      bus->InjectMessage("HEARTBEAT", hb);
    }
    PoseEstimate e;
    e.utime = clock.NowUtime();
    e.pose = Pose2(2, 3, 0);
    e.converged = true;
    bus->InjectMessage("POSE", ToLcm(e));
  }
  void Operator(int8_t command, int64_t seq) {
    coordinator_command_t c{};
    c.utime = clock.NowUtime();
    c.seq = seq;
    c.command = command;
    bus->InjectMessage("COORDINATOR_COMMAND", c);
  }
  void Status(int64_t id, int8_t state, float progress = 0.0f) {
    task_status_t s{};
    s.utime = clock.NowUtime();
    s.task_id = id;
    s.state = state;
    s.progress = progress;
    s.message = "test";
    bus->InjectMessage("TASK_STATUS", s);
  }
  path_t Path(int64_t id) {
    path_t p{};
    p.utime = clock.NowUtime();
    p.request_id = id;
    p.feasible = true;
    p.status = "ok";
    p.start.x = 2;
    p.start.y = 3;
    path_segment_t seg{};
    seg.motion = path_segment_t::FORWARD;
    seg.end.x = 10;
    seg.end.y = 3;
    seg.speed = 0.076;
    p.segments = {seg};
    p.num_segments = 1;
    p.length = 8;
    return p;
  }
  template <typename T>
  std::vector<T> Out(const std::string& channel) const {
    return bus->Decoded<T>(channel);
  }
  ManualClock clock{kT0};
  FakeRuntime fake{clock};
  FakeBus* bus = &fake.bus();
  NodeRuntime* runtime = &fake.runtime();
  CoordinatorNode node;
};

TEST(CoordinatorNodeTest, AStationIsDrivenThroughThePlannersAndTheTracker) {
  Harness h(Options());
  h.Tick(5);
  EXPECT_TRUE(h.Out<task_request_t>("TASK_REQUEST").empty()) << "no START yet";
  h.Operator(coordinator_command_t::START, 1);
  h.Tick(15);
  const auto requests = h.Out<task_request_t>("TASK_REQUEST");
  ASSERT_GE(requests.size(), 1u);
  EXPECT_EQ(requests[0].kind, task_request_t::SURVEY_NEXT);
  EXPECT_DOUBLE_EQ(requests[0].pose.x, 2.0);
  // The task planner proposes a station.
  TaskPlanMessage msg;
  msg.request_id = requests[0].request_id;
  TaskPlan& plan = msg.plan;
  plan.status = PlanStatus::kOk;
  Task station;
  station.id = 7;
  station.kind = TaskKind::kScanStation;
  station.target = Pose2(10, 3, 0);
  plan.tasks = {station};
  h.bus->InjectMessage("TASK_PLAN", TaskPlanToLcm(msg));
  h.Tick(2);
  const auto paths = h.Out<path_request_t>("PATH_REQUEST");
  ASSERT_EQ(paths.size(), 1u);
  EXPECT_DOUBLE_EQ(paths[0].goal.x, 10.0);
  EXPECT_DOUBLE_EQ(paths[0].start.x, 2.0);
  EXPECT_FALSE(paths[0].allow_unknown);
  // The planner's path goes to the tracker on DRIVE_PATH as it came.
  const path_t answer = h.Path(paths[0].request_id);
  h.bus->InjectMessage("PATH", answer);
  h.Tick(2);
  const auto driven = h.Out<path_t>("DRIVE_PATH");
  ASSERT_EQ(driven.size(), 1u);
  EXPECT_EQ(EncodeMessage(driven[0]), EncodeMessage(answer));
  // Unacknowledged: sent again after the resend period (2 s), the same bytes.
  h.Tick(21);
  ASSERT_EQ(h.Out<path_t>("DRIVE_PATH").size(), 2u);
  h.Status(paths[0].request_id, task_status_t::ACTIVE);
  h.Tick(30);
  EXPECT_EQ(h.Out<path_t>("DRIVE_PATH").size(), 2u) << "acknowledged: no more repeats";
  h.Status(paths[0].request_id, task_status_t::DONE);
  h.Tick(10);
  EXPECT_EQ(h.Out<task_request_t>("TASK_REQUEST").size(), requests.size() + 1) << "the next station, after the dwell";
  const auto status = h.Out<mission_status_t>("MISSION_STATUS");
  ASSERT_FALSE(status.empty());
  EXPECT_EQ(status.back().state, mission_status_t::RUNNING);
  EXPECT_EQ(status.back().num_nodes, static_cast<int32_t>(status.back().nodes.size()));
  EXPECT_EQ(status.back().nodes[0].name, "mission mission");
  EXPECT_EQ(status.back().nodes[0].parent, -1);
}

TEST(CoordinatorNodeTest, TheAdvanceCutsOnCutTaskAndThePauseCancelsIt) {
  CoordinatorNodeOptions o = Options();
  o.mission.explore = false;
  Harness h(o);
  h.Operator(coordinator_command_t::START, 1);
  h.Tick(15);
  const auto requests = h.Out<task_request_t>("TASK_REQUEST");
  ASSERT_EQ(requests.size(), 1u);
  EXPECT_EQ(requests[0].kind, task_request_t::ADVANCE);
  EXPECT_DOUBLE_EQ(requests[0].face.x, 40.0);
  TaskPlanMessage msg;
  msg.request_id = requests[0].request_id;
  TaskPlan& plan = msg.plan;
  plan.status = PlanStatus::kOk;
  Task cut;
  cut.id = 11;
  cut.kind = TaskKind::kBoxCut;
  cut.target = Pose2(34.9, 1.6, 0);
  cut.depth = 1.0;
  cut.width = 3.3;
  cut.face = Segment(40, 0, 40, 3.3);
  plan.tasks = {cut};
  h.bus->InjectMessage("TASK_PLAN", TaskPlanToLcm(msg));
  h.Tick(2);
  const auto cuts = h.Out<cutter_command_t>("CUT_TASK");
  ASSERT_EQ(cuts.size(), 1u);
  EXPECT_EQ(cuts[0].action, cutter_command_t::SUMP);
  EXPECT_DOUBLE_EQ(cuts[0].sump_depth, 1.0);
  EXPECT_DOUBLE_EQ(cuts[0].face_x1, 40.0);
  EXPECT_DOUBLE_EQ(cuts[0].face_y2, 3.3);
  h.Status(cuts[0].seq, task_status_t::ACTIVE, 0.25f);
  h.Tick(3);
  h.Operator(coordinator_command_t::PAUSE, 2);
  h.Tick(1);
  const auto after = h.Out<cutter_command_t>("CUT_TASK");
  ASSERT_EQ(after.size(), 2u);
  EXPECT_EQ(after[1].action, cutter_command_t::STOP);
  EXPECT_EQ(after[1].seq, cuts[0].seq);
  const auto drive = h.Out<drive_command_t>("DRIVE_COMMAND");
  ASSERT_FALSE(drive.empty());
  EXPECT_EQ(drive.back().mode, drive_command_t::STOP);
  EXPECT_EQ(h.Out<mission_status_t>("MISSION_STATUS").back().state, mission_status_t::PAUSED);
  // Resumed: the rest of the cut from where it got to (a quarter of a metre deeper).
  h.Operator(coordinator_command_t::RESUME, 3);
  h.Tick(2);
  const auto resumed = h.Out<cutter_command_t>("CUT_TASK");
  ASSERT_EQ(resumed.size(), 3u);
  EXPECT_NEAR(resumed[2].sump_depth, 0.75, 1e-6);
  EXPECT_NEAR(resumed[2].face_x1, 40.25, 1e-6);
}

TEST(CoordinatorNodeTest, EstopStopsTheVehicleEveryTickAndHostileMessagesAreCounted) {
  Harness h(Options());
  h.Operator(coordinator_command_t::ESTOP, 1);
  h.Tick(10);
  EXPECT_GE(h.Out<drive_command_t>("DRIVE_COMMAND").size(), 10u);
  EXPECT_EQ(h.Out<mission_status_t>("MISSION_STATUS").back().state, mission_status_t::ESTOPPED);
  const int64_t bad_before = h.bus->counters().messages_bad;
  heartbeat_t hb{};
  hb.process = "path_tracker";
  hb.state = 42;
  h.bus->InjectMessage("HEARTBEAT", hb);
  task_status_t st{};
  st.task_id = 1;
  st.state = task_status_t::ACTIVE;
  st.progress = std::numeric_limits<float>::quiet_NaN();
  h.bus->InjectMessage("TASK_STATUS", st);
  task_plan_t plan{};
  plan.status = 9;
  h.bus->InjectMessage("TASK_PLAN", plan);
  coordinator_command_t c{};
  c.command = 77;
  h.bus->InjectMessage("COORDINATOR_COMMAND", c);
  path_t p = h.Path(5);
  p.start.x = std::numeric_limits<double>::infinity();
  h.bus->InjectMessage("PATH", p);
  h.Tick(1);
  EXPECT_EQ(h.bus->counters().messages_bad - bad_before, 5);
  EXPECT_EQ(h.node.coordinator().state(), MissionState::kEstopped);
}

TEST(CoordinatorNodeTest, TheReportSaysWhatTheMissionDid) {
  testing::TempDir dir("coordinator_node_test");
  CoordinatorNodeOptions o = Options();
  o.report_out = (dir.path() / "mission.json").string();
  o.mission.explore = false;
  o.exit_when_done = true;
  Harness h(o);
  h.Operator(coordinator_command_t::START, 1);
  h.Tick(15);
  const auto requests = h.Out<task_request_t>("TASK_REQUEST");
  ASSERT_EQ(requests.size(), 1u);
  TaskPlanMessage msg;
  msg.request_id = requests[0].request_id;
  TaskPlan& plan = msg.plan;
  plan.status = PlanStatus::kFailed;
  plan.reason = "no face within 5 m of (40.0, 3.0)";
  h.bus->InjectMessage("TASK_PLAN", TaskPlanToLcm(msg));
  h.Tick(3);
  // plan_attempts = 2: asked once more (after the retry delay, 3 s), refused again; the
  // mission fails and says why.
  h.Tick(30);
  const auto again = h.Out<task_request_t>("TASK_REQUEST");
  ASSERT_EQ(again.size(), 2u);
  msg.request_id = again[1].request_id;
  h.bus->InjectMessage("TASK_PLAN", TaskPlanToLcm(msg));
  h.Tick(3);
  EXPECT_TRUE(h.runtime->StopRequested());
  const nlohmann::json j = nlohmann::json::parse(ReadFile(o.report_out));
  EXPECT_EQ(j["state"], "FAILED");
  EXPECT_NE(j["message"].get<std::string>().find("task planner: no face within 5 m of (40.0, 3.0) (after 2 attempts)"),
            std::string::npos)
      << j["message"];
  EXPECT_EQ(j["retries"], 1);
}

TEST(CoordinatorNodeTest, EveryOptionIsReachable) {
  const auto keys = ExpectEveryOptionReachable<CoordinatorNodeOptions>(
      CoordinatorNodeOptions{}, [](ConfigSchema& s, CoordinatorNodeOptions& o) { DeclareOptions(s, o); });
  EXPECT_EQ(keys.size(), 19u + 27u);  // 19 of the node, 27 of the mission
}

}  // namespace
}  // namespace minenav
