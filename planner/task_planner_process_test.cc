// task_planner as a process: --help names its channels, a bad start-up flag exits 2 in one
// line, and a batch run over a log (--log, --log-out) answers every request on TASK_PLAN,
// a repeated request_id with the same plan, the same bytes on a second run.

#include <gtest/gtest.h>

#include <vector>

#include "common/node/contour_map_conversions.h"
#include "common/node/event_log.h"
#include "minenav/task_plan_t.hpp"
#include "planner/task_plan_message.h"
#include "tests/child_process.h"
#include "tests/log_contents.h"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

constexpr int64_t kT0 = 1'000'000'000'000'000;

testing::ProgramRun RunTaskPlanner(const std::vector<std::string>& args, const std::string& output) {
  return testing::RunProgram(MINENAV_TASK_PLANNER_BIN, args, output, 120.0);
}

TEST(TaskPlannerProcess, HelpNamesTheChannelsAndABadFlagExits2InOneLine) {
  const testing::TempDir dir("task_planner_process");
  const testing::ProgramRun help = RunTaskPlanner({"--help"}, dir / "help.txt");
  EXPECT_EQ(help.exit_code, 0);
  for (const char* channel :
       {"subscribes task_request_t on 'TASK_REQUEST'", "subscribes contour_map_t on 'CONTOUR_MAP'",
        "subscribes line_map_t", "subscribes pose_estimate_t on 'POSE'", "publishes task_plan_t on 'TASK_PLAN'",
        "publishes heartbeat_t on 'HEARTBEAT'"})
    EXPECT_NE(help.output.find(channel), std::string::npos) << channel;
  EXPECT_EQ(help.output.find("SIM_TRUTH"), std::string::npos);
  const testing::ProgramRun bad = RunTaskPlanner({"--footprint", "0,10"}, dir / "bad.txt");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(testing::LinesContaining(bad.output, "--footprint W,L needs W > 0 and L > 0").size(), 1u) << bad.output;
}

TEST(TaskPlannerProcess, ABatchRunOverALogAnswersEveryRequestTheSameWayTwice) {
  const testing::TempDir dir("task_planner_process");
  {
    LogWriter log(dir / "in.lcm");
    // A 6.5 m entry with its last crosscut, seen whole (one closed contour).
    ContourMapMessage map;
    map.utime = kT0;
    map.version = 1;
    map.num_scans = 1;
    ContourPolyline outline;
    outline.closed = true;
    outline.points = {{0, -3.25}, {22, -3.25}, {22, -18}, {28, -18}, {28, -3.25}, {40, -3.25},
                      {40, 3.25}, {28, 3.25},  {28, 18},  {22, 18},  {22, 3.25},  {0, 3.25}};
    map.contours = {outline};
    log.Write("CONTOUR_MAP", ContourMapToLcm(map));
    TaskRequest advance;
    advance.utime = kT0 + 1'000'000;
    advance.request_id = 11;
    advance.mission_id = "batch";
    advance.kind = TaskRequestKind::kAdvance;
    advance.pose = Pose2(18, 0, 0);
    advance.face = Pose2(36, 0, 0);
    advance.depth = 1.0;
    advance.clearance = 0.1;
    log.Write("TASK_REQUEST", TaskRequestToLcm(advance));
    TaskRequest survey = advance;
    survey.utime = kT0 + 2'000'000;
    survey.request_id = 12;
    survey.kind = TaskRequestKind::kSurveyNext;
    log.Write("TASK_REQUEST", TaskRequestToLcm(survey));
    advance.utime = kT0 + 3'000'000;  // the coordinator re-sends: the same plan
    log.Write("TASK_REQUEST", TaskRequestToLcm(advance));
    log.Close();
  }
  for (const char* out : {"out1.lcm", "out2.lcm"}) {
    const testing::ProgramRun r = RunTaskPlanner({"--log", dir / "in.lcm", "--log-out", dir / out}, dir / "run.txt");
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  const auto plans = testing::ReadChannel<task_plan_t>(dir / "out1.lcm", "TASK_PLAN");
  ASSERT_EQ(plans.size(), 3u);
  const TaskPlanMessage advance = TaskPlanFromLcm(plans[0].msg), survey = TaskPlanFromLcm(plans[1].msg),
                        again = TaskPlanFromLcm(plans[2].msg);
  EXPECT_EQ(advance.request_id, 11);
  EXPECT_EQ(advance.mission_id, "batch");
  EXPECT_EQ(advance.plan.status, PlanStatus::kOk) << advance.plan.reason;
  EXPECT_EQ(advance.plan.tasks.size(), 5u);
  EXPECT_EQ(survey.request_id, 12);
  EXPECT_EQ(survey.plan.status, PlanStatus::kComplete) << survey.plan.reason;  // the map is closed
  EXPECT_EQ(again.request_id, 11);
  EXPECT_EQ(again.plan_id, advance.plan_id);
  EXPECT_EQ(again.plan.reason, advance.plan.reason);
  // Stamped with the log's clock, and the same bytes from the second run.
  EXPECT_EQ(plans[0].timestamp, kT0 + 1'000'000);
  EXPECT_EQ(testing::ReadPayloads(dir / "out1.lcm", "TASK_PLAN"), testing::ReadPayloads(dir / "out2.lcm", "TASK_PLAN"));
}

}  // namespace
}  // namespace minenav
