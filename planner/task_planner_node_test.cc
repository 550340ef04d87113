// task_planner's node on FakeRuntime: every request answered on TASK_PLAN with its id; an
// ADVANCE on a contour map (and on a LINE_MAP) gives the box cut, slab cut and back out with
// each maneuver judged by the independent checker; SURVEY_NEXT gives a station in the known
// free space, or COMPLETE; a repeated request_id gets the same plan without planning again;
// every bad request FAILED in one line and counted bad; a zlib map; the deadline named.

#include "planner/task_planner_node.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>
#include <vector>

#include "common/node/contour_map_conversions.h"
#include "common/node/conversions.h"
#include "common/node/fake_runtime.h"
#include "common/node/map_updates.h"
#include "minenav/pose_estimate_t.hpp"
#include "planner/test_maps.h"
#include "planner/testing/path_checker.h"

namespace minenav {
namespace {

constexpr int64_t kT0 = 1'000'000'000'000'000;

// A 6.5 m entry along +x from x = 0 to a face at x = 40, its last crosscut (6 m) 12 m before
// the face, seen from inside: one closed counter-clockwise contour.
std::vector<Eigen::Vector2d> EntryOutline() {
  return {{0, -3.25}, {22, -3.25}, {22, -18}, {28, -18}, {28, -3.25}, {40, -3.25},
          {40, 3.25}, {28, 3.25},  {28, 18},  {22, 18},  {22, 3.25},  {0, 3.25}};
}
std::vector<Segment> Closed(const std::vector<Eigen::Vector2d>& points) {
  std::vector<Segment> s;
  for (size_t k = 0; k < points.size(); ++k) s.emplace_back(points[k], points[(k + 1) % points.size()]);
  return s;
}

contour_map_t MapMessage(int64_t version, std::vector<ContourPolyline> contours,
                         int compress_above = kContourMapCompressAbove) {
  ContourMapMessage m;
  m.utime = kT0;
  m.version = version;
  m.num_scans = 1;
  m.contours = std::move(contours);
  return ContourMapToLcm(m, compress_above);
}

ContourPolyline Poly(std::vector<Eigen::Vector2d> points, bool closed) {
  ContourPolyline c;
  c.closed = closed;
  c.points = std::move(points);
  return c;
}

task_request_t Advance(int64_t id, const Pose2& pose, const Pose2& face, double depth = 1.0, double clearance = 0.1) {
  TaskRequest r;
  r.utime = kT0;
  r.request_id = id;
  r.mission_id = "m1";
  r.kind = TaskRequestKind::kAdvance;
  r.pose = pose;
  r.face = face;
  r.depth = depth;
  r.clearance = clearance;
  return TaskRequestToLcm(r);
}

task_request_t SurveyNext(int64_t id, const Pose2& pose, double clearance = 0.1) {
  TaskRequest r;
  r.utime = kT0;
  r.request_id = id;
  r.mission_id = "m1";
  r.kind = TaskRequestKind::kSurveyNext;
  r.pose = pose;
  r.clearance = clearance;
  return TaskRequestToLcm(r);
}

struct Harness {
  explicit Harness(TaskPlannerNodeOptions options = {}, Footprint footprint = Footprint::Rectangle(3.3, 10.0))
      : node(fake.runtime(), std::move(options), std::move(footprint)) {}
  // Runs the loop (real time passes for the worker) until `count` TASK_PLAN messages were
  // published or `seconds` passed.
  std::vector<task_plan_t> WaitForPlans(size_t count, double seconds = 60.0) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < until) {
      clock.Advance(20'000);
      fake.runtime().SpinOnce(0);
      if (fake.bus().PublishedOn("TASK_PLAN").size() >= count) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return fake.bus().Decoded<task_plan_t>("TASK_PLAN");
  }
  ManualClock clock{kT0};
  FakeRuntime fake{clock};
  TaskPlannerNode node;
};

std::vector<TaskKind> Kinds(const TaskPlan& plan) {
  std::vector<TaskKind> k;
  for (const Task& t : plan.tasks) k.push_back(t.kind);
  return k;
}

// Each driving task reachable from where the one before leaves the vehicle, judged by the
// independent checker on `walls` (Se2Planner run here).
void ExpectManeuversReachable(const std::vector<Segment>& walls, const Pose2& start, const TaskPlan& plan,
                              double clearance) {
  Se2PlannerOptions po;
  po.clearance = clearance;
  const Footprint miner = Footprint::Rectangle(3.3, 10.0);
  const Se2Planner planner(walls, miner, po);
  const testing::PathCheckSettings settings = planner_test::CheckSettings(miner.vertices, clearance, 0.05);
  Pose2 from = start;
  for (const Task& t : plan.tasks) {
    if (t.kind != TaskKind::kMove && t.kind != TaskKind::kBackOut) continue;
    const Se2PlanResult r = planner.Plan(from, t.target);
    ASSERT_EQ(r.status, SearchStatus::kFound) << t.description << ": " << r.reason;
    const auto report = testing::CheckPath(walls, from, planner_test::AsChecked(r.path), settings);
    EXPECT_TRUE(report.ok) << t.description << ": " << report.problem;
    from = t.target;
  }
}

TEST(TaskPlannerNode, AnAdvanceIsAnsweredWithTheCutsTaggedWithItsIdAndEveryManeuverReachable) {
  Harness h;
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(1, {Poly(EntryOutline(), true)}));
  h.fake.bus().InjectMessage("TASK_REQUEST", Advance(7, {18, 0, 0}, {36, 0, 0}));
  const std::vector<task_plan_t> plans = h.WaitForPlans(1);
  ASSERT_EQ(plans.size(), 1u);
  EXPECT_EQ(plans[0].request_id, 7);
  EXPECT_EQ(plans[0].plan_id, 1);
  EXPECT_EQ(plans[0].mission_id, "m1");
  const TaskPlanMessage p = TaskPlanFromLcm(plans[0]);
  ASSERT_EQ(p.plan.status, PlanStatus::kOk) << p.plan.reason;
  EXPECT_EQ(Kinds(p.plan), (std::vector<TaskKind>{TaskKind::kMove, TaskKind::kBoxCut, TaskKind::kMove,
                                                  TaskKind::kSlabCut, TaskKind::kBackOut}));
  EXPECT_EQ(
      p.plan.reason.rfind("advance the 6.50 m entry 1.00 m: box cut 3.30 m on the right, 1 slab cut of 2.10 m", 0), 0u)
      << p.plan.reason;
  for (size_t k = 0; k < p.plan.tasks.size(); ++k)
    EXPECT_EQ(p.plan.tasks[k].depends_on, k == 0 ? -1 : static_cast<int64_t>(k));
  EXPECT_EQ(p.plan.tasks[1].appendages, Appendages::kCutting);
  EXPECT_EQ(p.plan.tasks[4].appendages, Appendages::kStowed);
  ExpectManeuversReachable(Closed(EntryOutline()), {18, 0, 0}, p.plan, 0.1);
}

TEST(TaskPlannerNode, ARepeatedRequestIdGetsTheSamePlanWithoutPlanningAgain) {
  Harness h;
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(1, {Poly(EntryOutline(), true)}));
  h.fake.bus().InjectMessage("TASK_REQUEST", Advance(3, {18, 0, 0}, {36, 0, 0}));
  h.fake.bus().InjectMessage("TASK_REQUEST",
                             Advance(3, {18, 0, 0}, {36, 0, 0}));  // while it is planned: not queued again
  ASSERT_EQ(h.WaitForPlans(1).size(), 1u);
  h.WaitForPlans(2, 0.3);
  EXPECT_EQ(h.fake.bus().PublishedOn("TASK_PLAN").size(), 1u);
  // The coordinator did not hear it and sends it again: the same plan, not planned anew.
  h.fake.bus().InjectMessage("TASK_REQUEST", Advance(3, {18, 0, 0}, {36, 0, 0}));
  const std::vector<task_plan_t> plans = h.WaitForPlans(2);
  ASSERT_EQ(plans.size(), 2u);
  EXPECT_EQ(plans[1].plan_id, plans[0].plan_id);
  EXPECT_EQ(plans[1].request_id, 3);
  EXPECT_EQ(plans[1].reason, plans[0].reason);
  ASSERT_EQ(plans[1].num_tasks, plans[0].num_tasks);
  for (int k = 0; k < plans[0].num_tasks; ++k) {
    EXPECT_EQ(plans[1].tasks[static_cast<size_t>(k)].target.x, plans[0].tasks[static_cast<size_t>(k)].target.x);
    EXPECT_EQ(plans[1].tasks[static_cast<size_t>(k)].description, plans[0].tasks[static_cast<size_t>(k)].description);
  }
  EXPECT_EQ(h.node.plans(), 1);
  EXPECT_EQ(h.node.repeats(), 1);
}

TEST(TaskPlannerNode, RequestsOnOneMapVersionShareItsPlannersAndANewVersionBuildsItsOwn) {
  Harness h;
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(1, {Poly(EntryOutline(), true)}));
  h.fake.bus().InjectMessage("TASK_REQUEST", Advance(1, {18, 0, 0}, {36, 0, 0}));
  ASSERT_EQ(h.WaitForPlans(1).size(), 1u);
  const int64_t first = h.node.planners_built();
  EXPECT_EQ(first, 1);  // the maneuvers' planner at the request's clearance
  // Another advance on the same map, from elsewhere: the same planner plans it.
  h.fake.bus().InjectMessage("TASK_REQUEST", Advance(2, {16, 0, 0}, {36, 0, 0}));
  const std::vector<task_plan_t> plans = h.WaitForPlans(2);
  ASSERT_EQ(plans.size(), 2u);
  EXPECT_EQ(TaskPlanFromLcm(plans[1]).plan.status, PlanStatus::kOk) << plans[1].reason;
  EXPECT_EQ(h.node.planners_built(), first);
  // A new version of the map: planned on its own planner.
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(2, {Poly(EntryOutline(), true)}));
  h.fake.bus().InjectMessage("TASK_REQUEST", Advance(3, {18, 0, 0}, {36, 0, 0}));
  ASSERT_EQ(h.WaitForPlans(3).size(), 3u);
  EXPECT_EQ(h.node.planners_built(), first + 1);
}

TEST(TaskPlannerNode, SurveyNextGivesAStationBeforeTheFrontierThenCompleteOnAClosedMap) {
  Harness h({}, Footprint::Rectangle(1.2, 2.0));  // a compact ladar carrier
  // A corridor 30 x 6 m seen from its west end: its east end is unknown (the open contour's
  // ends are joined by a frontier across x = 30).
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(1, {Poly({{30, 6}, {0, 6}, {0, 0}, {30, 0}}, false)}));
  h.fake.bus().InjectMessage("TASK_REQUEST", SurveyNext(1, {5, 3, 0}));
  std::vector<task_plan_t> plans = h.WaitForPlans(1);
  ASSERT_EQ(plans.size(), 1u);
  TaskPlanMessage p = TaskPlanFromLcm(plans[0]);
  ASSERT_EQ(p.plan.status, PlanStatus::kOk) << p.plan.reason;
  ASSERT_EQ(p.plan.tasks.size(), 1u);
  const Task& station = p.plan.tasks[0];
  EXPECT_EQ(station.kind, TaskKind::kScanStation);
  // Inside the corridor, at least 1.5 m from its walls (min_wall_distance), within 12 m of the
  // frontier (max_standoff).
  EXPECT_GE(station.target.x, 30.0 - 12.0);
  EXPECT_LE(station.target.x, 30.0 - 1.5);
  EXPECT_GE(station.target.y, 1.5);
  EXPECT_LE(station.target.y, 4.5);
  EXPECT_NE(p.plan.reason.find("before frontier"), std::string::npos) << p.plan.reason;
  // The corridor seen whole: closed, nothing left.
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(2, {Poly({{0, 0}, {30, 0}, {30, 6}, {0, 6}}, true)}));
  h.fake.bus().InjectMessage("TASK_REQUEST", SurveyNext(2, station.target));
  plans = h.WaitForPlans(2);
  ASSERT_EQ(plans.size(), 2u);
  p = TaskPlanFromLcm(plans[1]);
  EXPECT_EQ(p.plan.status, PlanStatus::kComplete) << p.plan.reason;
  EXPECT_EQ(p.plan.reason.rfind("no frontier left", 0), 0u) << p.plan.reason;
  EXPECT_EQ(plans[1].request_id, 2);
}

// A request before any map, within first_map_wait of the start, is left for its repeat (a
// task planner restarted mid-mission answered the coordinator's repeated request "no map" and
// the mission FAILED); after the map its repeat is planned.
TEST(TaskPlannerNode, ARequestBeforeTheFirstMapIsLeftForItsRepeat) {
  TaskPlannerNodeOptions o;
  o.first_map_wait = 10.0;
  Harness h(o);
  h.fake.bus().InjectMessage("TASK_REQUEST", Advance(1, {18, 0, 0}, {36, 0, 0}));
  EXPECT_TRUE(h.WaitForPlans(1, 0.3).empty()) << "answered without a map";
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(1, {Poly(EntryOutline(), true)}));
  h.fake.bus().InjectMessage("TASK_REQUEST", Advance(1, {18, 0, 0}, {36, 0, 0}));  // the repeat
  const std::vector<task_plan_t> plans = h.WaitForPlans(1);
  ASSERT_EQ(plans.size(), 1u);
  EXPECT_EQ(plans[0].request_id, 1);
  EXPECT_EQ(plans[0].status, task_plan_t::OK) << plans[0].reason;
}

TEST(TaskPlannerNode, EveryBadRequestIsAnsweredFailedInOneLineAndCountedBad) {
  TaskPlannerNodeOptions no_wait;
  no_wait.first_map_wait = 0.0;  // "no map" answered at once
  Harness h(no_wait);
  h.fake.bus().InjectMessage("TASK_REQUEST", Advance(1, {18, 0, 0}, {36, 0, 0}));  // no map yet
  h.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(1, {Poly(EntryOutline(), true)}));
  task_request_t kind = Advance(2, {18, 0, 0}, {36, 0, 0});
  kind.kind = 9;
  task_request_t nan_pose = Advance(3, {std::nan(""), 0, 0}, {36, 0, 0});
  task_request_t nan_face = Advance(4, {18, 0, 0}, {36, std::nan(""), 0});
  task_request_t depth = Advance(5, {18, 0, 0}, {36, 0, 0}, 0.0);
  task_request_t clearance = Advance(6, {18, 0, 0}, {36, 0, 0}, 1.0, 5.0);
  task_request_t deep = Advance(7, {18, 0, 0}, {36, 0, 0}, 50.0);  // valid message, refused by the planner
  for (const auto& r : {kind, nan_pose, nan_face, depth, clearance, deep})
    h.fake.bus().InjectMessage("TASK_REQUEST", r);
  const std::vector<task_plan_t> plans = h.WaitForPlans(7);
  ASSERT_EQ(plans.size(), 7u);
  const char* expected[] = {"no map: nothing received on CONTOUR_MAP yet",
                            "invalid request: unknown kind 9 (SURVEY_NEXT 0, ADVANCE 1)",
                            "invalid request: pose",
                            "invalid request: face is not finite",
                            "invalid request: depth 0.000000 m is not > 0",
                            "invalid request: clearance 5.00 m is not in [0, 2.00] (max_clearance)",
                            "depth 50.00 m is not in (0, 10.00] (max_depth)"};
  for (size_t k = 0; k < plans.size(); ++k) {
    EXPECT_EQ(plans[k].request_id, static_cast<int64_t>(k) + 1);
    EXPECT_EQ(plans[k].status, task_plan_t::FAILED);
    EXPECT_EQ(plans[k].num_tasks, 0);
    EXPECT_EQ(plans[k].reason.rfind(expected[k], 0), 0u) << plans[k].reason;
    EXPECT_EQ(plans[k].reason.find('\n'), std::string::npos);
  }
  // The five malformed ones are bad messages (HEARTBEAT messages_bad); no map and too deep are not.
  EXPECT_EQ(h.fake.bus().counters().messages_bad, 5);
}

TEST(TaskPlannerNode, AZlibMapALineMapAndTheDeadline) {
  TaskPlannerNodeOptions options;
  options.first_map_wait = 0.0;  // "no map" answered at once
  options.line_map_channel = "LINE_MAP";
  Harness h(options);
  // A line map: ADVANCE plans on it (no contour map at all).
  h.fake.bus().InjectMessage("LINE_MAP", SegmentsToLcm(Closed(EntryOutline()), kT0, 1, "entry"));
  h.fake.bus().InjectMessage("TASK_REQUEST", Advance(1, {18, 0, 0}, {36, 0, 0}));
  std::vector<task_plan_t> plans = h.WaitForPlans(1);
  ASSERT_EQ(plans.size(), 1u);
  EXPECT_EQ(plans[0].status, task_plan_t::OK) << plans[0].reason;
  // SURVEY_NEXT needs the contour map: a compressed one.
  const contour_map_t zipped = MapMessage(1, {Poly({{30, 6}, {0, 6}, {0, 0}, {30, 0}}, false)}, 0);
  ASSERT_EQ(zipped.encoding, contour_map_t::ENCODING_ZLIB);
  h.fake.bus().InjectMessage("TASK_REQUEST", SurveyNext(2, {10, 3, 0}));
  h.fake.bus().InjectMessage("CONTOUR_MAP", zipped);
  h.fake.bus().InjectMessage("TASK_REQUEST", SurveyNext(3, {10, 3, 0}));
  plans = h.WaitForPlans(3);
  ASSERT_EQ(plans.size(), 3u);
  EXPECT_EQ(plans[1].reason, "no map: nothing received on CONTOUR_MAP yet");
  EXPECT_EQ(plans[2].request_id, 3);
  EXPECT_EQ(plans[2].status, task_plan_t::OK) << plans[2].reason;  // the miner drives on along the corridor
  EXPECT_NE(plans[2].reason.find("before frontier 0"), std::string::npos) << plans[2].reason;

  // A deadline too short for the maneuver checks: the plan fails and says why.
  TaskPlannerNodeOptions hurry;
  hurry.deadline = 0.001;
  Harness late(hurry);
  late.fake.bus().InjectMessage("CONTOUR_MAP", MapMessage(1, {Poly(EntryOutline(), true)}));
  late.fake.bus().InjectMessage("TASK_REQUEST", Advance(1, {18, 0, 0}, {36, 0, 0}));
  plans = late.WaitForPlans(1);
  ASSERT_EQ(plans.size(), 1u);
  EXPECT_EQ(plans[0].status, task_plan_t::FAILED);
  // Which maneuver the deadline stops depends on the machine (the move into position is one
  // free analytic shot, tens of microseconds; the slab cut's reposition a search of ms).
  EXPECT_EQ(plans[0].reason.rfind("deadline: planning was stopped at 0.001 s: ", 0), 0u) << plans[0].reason;
  const bool names_a_maneuver = plans[0].reason.find("move into position for the box cut: ") != std::string::npos ||
                                plans[0].reason.find("reposition for slab cut ") != std::string::npos ||
                                plans[0].reason.find("back out") != std::string::npos;
  EXPECT_TRUE(names_a_maneuver) << plans[0].reason;
  EXPECT_NE(plans[0].reason.find("stopped"), std::string::npos) << plans[0].reason;
}

TEST(TaskPlannerNode, OptionsAreValidated) {
  TaskPlannerNodeOptions o;
  EXPECT_EQ(ValidateOptions(o), "");
  o.advance.box_cut_side = "up";
  EXPECT_EQ(ValidateOptions(o), "advance.box_cut_side must be right or left");
  o = {};
  o.survey.min_overlap = 2.0;
  EXPECT_EQ(ValidateOptions(o), "survey.min_overlap must be in [0, 1]");
  o = {};
  o.default_clearance = 3.0;
  EXPECT_EQ(ValidateOptions(o), "default_clearance must not exceed max_clearance");
}

}  // namespace
}  // namespace minenav
