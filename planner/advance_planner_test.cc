// Advancing an entry (advance_planner.h): the subtasks for entries 6, 6.5, 7 and 8 m wide,
// an oblique face, a narrow entry, the generated mine's boundary face; the refusals (no entry
// walls, a hint at nothing or at a frontier, a face too oblique, an unreachable goal). Every
// goal is measured against the true walls by brute force (testing/path_checker.h's
// PoseClearance), and every maneuver is planned again here with Se2Planner and its path
// judged by the independent checker.

#include "planner/advance_planner.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "common/angle.h"
#include "planner/test_maps.h"
#include "planner/testing/path_checker.h"
#include "sim/mine_generator.h"

namespace minenav {
namespace {

constexpr double kReach = 5.0, kDrum = 3.3, kStandoff = 0.1;
const double kMargin = AdvanceOptions{}.side_margin;  // 0.45 m

// The closed polygon's edges split into pieces of at most `piece` m, each inner vertex moved
// across its edge by a uniform value in [-jitter, jitter]: walls as a mine has them.
std::vector<Segment> JitteredPolygon(const std::vector<Eigen::Vector2d>& corners, double piece, double jitter,
                                     uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> offset(-jitter, jitter);
  std::vector<Eigen::Vector2d> points;
  for (size_t k = 0; k < corners.size(); ++k) {
    const Eigen::Vector2d a = corners[k], b = corners[(k + 1) % corners.size()];
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / piece)));
    const Eigen::Vector2d d = (b - a).normalized(), normal(-d.y(), d.x());
    for (int i = 0; i < n; ++i) points.push_back(a + (b - a) * i / n + (i == 0 ? 0.0 : offset(rng)) * normal);
  }
  std::vector<Segment> walls;
  for (size_t k = 0; k < points.size(); ++k) walls.emplace_back(points[k], points[(k + 1) % points.size()]);
  return walls;
}

// An entry along +x, `width` wide about y = 0, from x = 0 (a wall) to a face through
// (length, 0) whose normal is turned `face_angle` from +x; unless `dead_end`, the last crosscut
// (6 m wide, 15 m each side) crosses it a pillar's length (12 m) before the face, as in a
// room-and-pillar section being developed. Counter-clockwise (free space on the left, as a
// contour map has it).
struct Entry {
  double width, length = 40.0, face_angle = 0.0;
  double jitter = 0.05;
  bool dead_end = false;
  Eigen::Vector2d FacePoint() const { return {length, 0.0}; }
  Eigen::Vector2d FaceNormal() const { return {std::cos(face_angle), std::sin(face_angle)}; }
  std::vector<Segment> Walls() const {
    const double h = 0.5 * width, t = std::tan(face_angle);
    const double x1 = length - 12.0, x0 = x1 - 6.0, arm = h + 15.0;
    if (dead_end) return JitteredPolygon({{0, -h}, {length + h * t, -h}, {length - h * t, h}, {0, h}}, 1.0, jitter, 7);
    return JitteredPolygon({{0, -h},
                            {x0, -h},
                            {x0, -arm},
                            {x1, -arm},
                            {x1, -h},
                            {length + h * t, -h},
                            {length - h * t, h},
                            {x1, h},
                            {x1, arm},
                            {x0, arm},
                            {x0, h},
                            {0, h}},
                           1.0, jitter, 7);
  }
};

Footprint Miner() { return Footprint::Rectangle(3.3, 10.0); }

AdvanceRequest Request(const Pose2& vehicle, const Eigen::Vector2d& hint, double direction, double depth = 1.0,
                       double clearance = 0.1) {
  AdvanceRequest r;
  r.vehicle = vehicle;
  r.face_hint = hint;
  r.direction = direction;
  r.depth = depth;
  r.clearance = clearance;
  return r;
}

std::vector<TaskKind> Kinds(const TaskPlan& plan) {
  std::vector<TaskKind> k;
  for (const Task& t : plan.tasks) k.push_back(t.kind);
  return k;
}

// Everything a plan to advance an entry must be, measured on the true walls: the face line
// through `face_point` with normal `normal` (into the coal); `jitter` m of wall wander.
void ExpectAdvancePlan(const std::vector<Segment>& walls, const AdvanceRequest& request, const AdvanceResult& result,
                       const Eigen::Vector2d& face_point, const Eigen::Vector2d& normal, double jitter,
                       int expected_slabs, double expected_total_width) {
  const TaskPlan& plan = result.plan;
  ASSERT_EQ(plan.status, PlanStatus::kOk) << plan.reason;
  std::vector<TaskKind> expected = {TaskKind::kMove, TaskKind::kBoxCut};
  for (int k = 0; k < expected_slabs; ++k) expected.insert(expected.end(), {TaskKind::kMove, TaskKind::kSlabCut});
  expected.push_back(TaskKind::kBackOut);
  ASSERT_EQ(Kinds(plan), expected) << plan.reason;
  const double heading = std::atan2(normal.y(), normal.x());
  double total_width = 0.0;
  for (size_t k = 0; k < plan.tasks.size(); ++k) {
    const Task& t = plan.tasks[k];
    SCOPED_TRACE(t.description);
    EXPECT_EQ(t.id, static_cast<int64_t>(k) + 1);
    EXPECT_EQ(t.depends_on, k == 0 ? -1 : static_cast<int64_t>(k));
    // Squared to the face (the fit of a jittered face: within a degree and a half).
    EXPECT_LT(std::abs(NormalizeAngle(t.target.theta - heading)), DegToRad(1.5));
    const Eigen::Vector2d drum_front = t.target * Eigen::Vector2d(kReach, 0.0);
    const double to_face = normal.dot(face_point - drum_front);  // along the normal, to the true face line
    const double clearance = testing::PoseClearance(walls, Miner().vertices, t.target);
    if (t.kind == TaskKind::kMove) {
      EXPECT_EQ(t.appendages, Appendages::kStowed);
      EXPECT_TRUE(t.allow_reverse);
      EXPECT_DOUBLE_EQ(t.clearance, request.clearance);
      // Clear of every true wall by the clearance, the drum its standoff + clearance from the face.
      EXPECT_GE(clearance, request.clearance);
      EXPECT_NEAR(to_face, kStandoff + request.clearance, 2.0 * jitter + 0.02);
      // The cut that follows starts straight ahead of it, the drum standoff from the face:
      // the tram there touches nothing, and the vehicle stands there exactly standoff from the
      // nearest face point (by brute force).
      const Task& cut = plan.tasks[k + 1];
      const double at_cut = testing::PoseClearance(walls, Miner().vertices, cut.target);
      EXPECT_GE(at_cut, kStandoff - 1e-9);
      EXPECT_LE(at_cut, kStandoff + 0.02);
      const double tram = (cut.target.translation() - t.target.translation()).norm();
      EXPECT_NEAR(tram, request.clearance, 1e-9);
      const auto straight =
          testing::CheckPath(walls, t.target, {{0, cut.target}}, planner_test::CheckSettings(Miner().vertices, 0.0));
      EXPECT_TRUE(straight.ok) << straight.problem;
    } else if (t.kind == TaskKind::kBoxCut || t.kind == TaskKind::kSlabCut) {
      EXPECT_EQ(t.appendages, Appendages::kCutting);
      EXPECT_DOUBLE_EQ(t.depth, request.depth);
      if (t.kind == TaskKind::kBoxCut) {
        EXPECT_DOUBLE_EQ(t.width, kDrum);
      }
      total_width += t.width;
      // The face as the drum meets it: on the true face line, a drum wide, free space on its left.
      EXPECT_NEAR(t.face.length(), kDrum, 1e-9);
      EXPECT_LT(std::abs(normal.dot(t.face.a - face_point)), 2.0 * jitter + 0.05);
      EXPECT_LT(std::abs(normal.dot(t.face.b - face_point)), 2.0 * jitter + 0.05);
      EXPECT_GT(SignedDistanceToLine(t.target.translation(), t.face), 0.0);
      // The vehicle's centre projects inside it (the cutter refuses a face not ahead).
      EXPECT_EQ(ProjectOntoSegment(t.target.translation(), t.face).region, SegmentRegion::kInterior);
    } else {
      EXPECT_EQ(t.appendages, Appendages::kStowed);
      EXPECT_TRUE(t.allow_reverse);
      EXPECT_GE(clearance, request.clearance);
      // The drum bolter_gap behind the advanced face, back from the last cut along the entry's
      // axis (straight back when the face is square), still squared to the face.
      EXPECT_NEAR(to_face + request.depth, AdvanceOptions{}.bolter_gap, 2.0 * jitter + 0.05);
      const Pose2 to_entry = result.entry->entry_frame.inverse();
      const Pose2& last_cut = plan.tasks[k - 1].target;
      EXPECT_NEAR((to_entry * t.target).y, (to_entry * last_cut).y, 1e-6);
      EXPECT_NEAR(NormalizeAngle(t.target.theta - last_cut.theta), 0.0, 1e-9);
    }
  }
  if (expected_total_width > 0.0) {
    EXPECT_NEAR(total_width, expected_total_width, 2.0 * jitter + 0.05) << plan.reason;
  }
  // The box cut on the right rib (looking at the face), the last slab cut on the left.
  const Eigen::Vector2d left(-normal.y(), normal.x());
  EXPECT_LT(left.dot(plan.tasks[1].target.translation() - face_point),
            left.dot(plan.tasks[plan.tasks.size() - 2].target.translation() - face_point));

  // Every maneuver, planned again here from where the task before leaves the vehicle, and
  // judged by the independent checker against the true walls.
  Se2PlannerOptions po;
  po.clearance = request.clearance;
  const Se2Planner planner(walls, Miner(), po);
  Pose2 from = request.vehicle;
  int maneuvers = 0;
  for (const Task& t : plan.tasks) {
    if (t.kind != TaskKind::kMove && t.kind != TaskKind::kBackOut) continue;
    SCOPED_TRACE(t.description);
    const Se2PlanResult r = planner.Plan(from, t.target);
    ASSERT_EQ(r.status, SearchStatus::kFound) << r.reason;
    const auto settings = planner_test::CheckSettings(Miner().vertices, request.clearance);
    const auto report = testing::CheckPath(walls, from, planner_test::AsChecked(r.path), settings);
    EXPECT_TRUE(report.ok) << report.problem;
    // The library's own check went the same way.
    ASSERT_LT(static_cast<size_t>(maneuvers), result.maneuvers.size());
    const ManeuverCheck& m = result.maneuvers[static_cast<size_t>(maneuvers)];
    EXPECT_EQ(m.start.translation(), from.translation());
    EXPECT_EQ(m.goal.translation(), t.target.translation());
    const auto library = testing::CheckPath(walls, m.start, planner_test::AsChecked(m.result.path), settings);
    EXPECT_TRUE(library.ok) << library.problem;
    ++maneuvers;
    from = t.target;
  }
  EXPECT_EQ(maneuvers, expected_slabs + 2);
}

struct EntryCase {
  double width;
  int slabs;
};

class AdvanceAnEntry : public ::testing::TestWithParam<EntryCase> {};

TEST_P(AdvanceAnEntry, BoxCutSlabCutsAndBackOutEveryGoalReachable) {
  const EntryCase c = GetParam();
  Entry entry{c.width};
  const std::vector<Segment> walls = entry.Walls();
  const AdvanceRequest request = Request({entry.length - 22.0, 0.3, 0.05}, {entry.length - 4.0, 0.5}, 0.0, 1.0);
  const AdvanceResult result = PlanAdvance(TaskMapFromSegments(walls), Miner(), request, {}, {});
  // The width between the ribs less clearance + margin at each.
  ExpectAdvancePlan(walls, request, result, entry.FacePoint(), entry.FaceNormal(), entry.jitter, c.slabs,
                    c.width - 2.0 * (request.clearance + kMargin));
  ASSERT_TRUE(result.entry.has_value());
  EXPECT_NEAR(result.entry->width, c.width, 2.0 * entry.jitter);
  EXPECT_LT(std::abs(result.entry->face_angle), DegToRad(1.0));
  std::printf("entry %.1f m: %s\n", c.width, result.plan.reason.c_str());
}

INSTANTIATE_TEST_SUITE_P(Widths, AdvanceAnEntry,
                         ::testing::Values(EntryCase{6.0, 1}, EntryCase{6.5, 1}, EntryCase{7.0, 1}, EntryCase{8.0, 2}),
                         [](const ::testing::TestParamInfo<EntryCase>& i) {
                           return "W" + std::to_string(static_cast<int>(i.param.width * 10));
                         });

TEST(AdvancePlanner, AFaceNotSquareToTheEntryIsCutSquaredToTheFace) {
  Entry entry{6.5};
  entry.face_angle = DegToRad(8.0);
  const std::vector<Segment> walls = entry.Walls();
  const AdvanceRequest request = Request({entry.length - 22.0, 0.0, 0.0}, {entry.length - 4.0, 0.0}, 0.0, 1.5);
  const AdvanceResult result = PlanAdvance(TaskMapFromSegments(walls), Miner(), request, {}, {});
  ASSERT_EQ(result.plan.status, PlanStatus::kOk) << result.plan.reason;
  ASSERT_TRUE(result.entry.has_value());
  EXPECT_NEAR(result.entry->face_angle, DegToRad(8.0), DegToRad(1.0));
  EXPECT_NEAR(result.entry->axis, 0.0, DegToRad(1.0));
  // Squared to the face, the vehicle is at 8 degrees to the ribs: less room across it.
  const double across = 10.0 * std::sin(DegToRad(8.0)) + 3.3 * std::cos(DegToRad(8.0));
  EXPECT_LT(across, 6.5 - 2 * 0.2);
  ExpectAdvancePlan(walls, request, result, entry.FacePoint(), entry.FaceNormal(), entry.jitter, 1, -1.0 /*below*/);
}

TEST(AdvancePlanner, ANarrowEntryIsOneBoxCutTheWholeWidth) {
  Entry entry{3.9};
  const std::vector<Segment> walls = entry.Walls();
  AdvanceOptions options;
  options.drum_width = 4.0;  // a drum wider than the entry (and than the 3.3 m vehicle)
  const AdvanceRequest request = Request({entry.length - 20.0, 0.0, 0.0}, {entry.length - 4.0, 0.0}, 0.0, 1.0, 0.05);
  const AdvanceResult result = PlanAdvance(TaskMapFromSegments(walls), Miner(), request, options, {});
  ASSERT_EQ(result.plan.status, PlanStatus::kOk) << result.plan.reason;
  EXPECT_EQ(Kinds(result.plan), (std::vector<TaskKind>{TaskKind::kMove, TaskKind::kBoxCut, TaskKind::kBackOut}));
  EXPECT_NE(result.plan.reason.find("narrower than the drum"), std::string::npos) << result.plan.reason;
  EXPECT_NE(result.plan.reason.find("the box cut is the whole width"), std::string::npos) << result.plan.reason;
  const Task& box = result.plan.tasks[1];
  // The whole width the vehicle can back straight out of, squared to the face (whose fit on
  // 3.9 m of jittered face is a few tenths of a degree off: 20 m back that is 0.1 m).
  EXPECT_LE(box.width, 3.9 + 2.0 * entry.jitter);
  EXPECT_GE(box.width, 3.6);
  EXPECT_NEAR(box.target.y, 0.0, 2.0 * entry.jitter + 0.02);  // centred
  EXPECT_GE(testing::PoseClearance(walls, Miner().vertices, result.plan.tasks[0].target), 0.05);
  for (const ManeuverCheck& m : result.maneuvers)
    EXPECT_TRUE(testing::CheckPath(walls, m.start, planner_test::AsChecked(m.result.path),
                                   planner_test::CheckSettings(Miner().vertices, 0.05))
                    .ok);
}

TEST(AdvancePlanner, TheGeneratedMinesBoundaryFaceAtTheEndOfAnEntry) {
  // The simulated mine: the faces to advance are the boundary wall where an entry meets it
  // (across the last crosscut: the entry's ribs end 6 m before the face).
  MineOptions mine;  // 2 x 3 pillars of 12 m, 6 m rooms, walls wander up to 0.6 m
  const std::vector<Segment> world = GenerateRoomAndPillarMine(mine);
  const double y = mine.room_width + mine.pillar_size + 0.5 * mine.room_width;  // the middle entry: 21 m
  const double face_x = MinePanelSize(mine).x();                                // 60 m
  const AdvanceRequest request = Request({40.0, y, 0.0}, {50.0, y}, 0.0, 1.0);
  const AdvanceResult result = PlanAdvance(TaskMapFromSegments(world), Miner(), request, {}, {});
  ASSERT_EQ(result.plan.status, PlanStatus::kOk) << result.plan.reason;
  ASSERT_TRUE(result.entry.has_value());
  EXPECT_NEAR(result.entry->width, 6.0, 0.8);
  // The ribs' lines (the pillars') carried across the crosscut: the cuts stay in the entry.
  ExpectAdvancePlan(world, request, result, {face_x, y}, {1.0, 0.0}, 0.6, 1, -1.0);
  for (const Task& t : result.plan.tasks)
    if (t.kind == TaskKind::kBoxCut || t.kind == TaskKind::kSlabCut) {
      EXPECT_GT(std::min(t.face.a.y(), t.face.b.y()), y - 3.0 - 0.6);
      EXPECT_LT(std::max(t.face.a.y(), t.face.b.y()), y + 3.0 + 0.6);
    }
  std::printf("generated mine: %s\n", result.plan.reason.c_str());
}

TEST(AdvancePlanner, AHintAtNothingOrAtAFrontierIsRefused) {
  Entry entry{6.0};
  const std::vector<Segment> walls = entry.Walls();
  // Back down the entry: the wall at x = 0 is 36 m away, beyond max_face_distance (15 m).
  AdvanceResult r = PlanAdvance(TaskMapFromSegments(walls), Miner(),
                                Request({entry.length - 20, 0, 0}, {entry.length - 4.0, 0}, kPi), {}, {});
  EXPECT_EQ(r.plan.status, PlanStatus::kFailed);
  EXPECT_TRUE(r.plan.tasks.empty());
  EXPECT_EQ(r.plan.reason.rfind("the face hint points at nothing: no wall within 15.00 m ahead of (36.00, 0.00)", 0),
            0u)
      << r.plan.reason;
  // A contour map whose entry ends in a frontier (the face not seen yet).
  TaskMap unseen;
  unseen.oriented = true;
  unseen.walls = {{0, -3, 40, -3}, {40, 3, 0, 3}, {0, 3, 0, -3}};
  unseen.frontiers = {{40, -3, 40, 3}};
  r = PlanAdvance(unseen, Miner(), Request({20, 0, 0}, {36, 0}, 0.0), {}, {});
  EXPECT_EQ(r.plan.status, PlanStatus::kFailed);
  EXPECT_EQ(r.plan.reason.rfind("the face hint points at unexplored space: a frontier 4.00 m ahead", 0), 0u)
      << r.plan.reason;
  // A hint inside a pillar of a contour map sees the back of a wall.
  TaskMap room;
  room.oriented = true;
  room.walls = {{0, 0, 30, 0},   {30, 0, 30, 20},  {30, 20, 0, 20}, {0, 20, 0, 0},    // the room, counter-clockwise
                {10, 8, 10, 12}, {10, 12, 14, 12}, {14, 12, 14, 8}, {14, 8, 10, 8}};  // a pillar, clockwise
  r = PlanAdvance(room, Miner(), Request({5, 5, 0}, {12, 10}, 0.0), {}, {});
  EXPECT_EQ(r.plan.reason.rfind("the face hint is not in free space", 0), 0u) << r.plan.reason;
  // Not finite.
  r = PlanAdvance(room, Miner(), Request({5, 5, 0}, {std::nan(""), 10}, 0.0), {}, {});
  EXPECT_EQ(r.plan.reason, "the face hint is not finite");
}

TEST(AdvancePlanner, AFaceWithoutEntryWallsIsRefused) {
  // A wide room: the wall ahead has no ribs within 8 m of the way to it.
  const std::vector<Segment> room = JitteredPolygon({{0, 0}, {40, 0}, {40, 40}, {0, 40}}, 1.0, 0.05, 3);
  const AdvanceResult r = PlanAdvance(TaskMapFromSegments(room), Miner(), Request({20, 20, 0}, {30, 20}, 0.0), {}, {});
  EXPECT_EQ(r.plan.status, PlanStatus::kFailed);
  EXPECT_EQ(r.plan.reason.rfind("no entry walls found: 0 left and 0 right of 80 rays met a wall along the way within "
                                "8.00 m of the 20.00 m before the face at (39.",
                                0),
            0u)
      << r.plan.reason;
  // One rib only: a wall on the right, open to the left.
  std::vector<Segment> one_sided = JitteredPolygon({{0, 0}, {40, 0}, {40, 40}, {0, 40}}, 1.0, 0.05, 3);
  one_sided.push_back({0, 17, 40, 17});
  const AdvanceResult one =
      PlanAdvance(TaskMapFromSegments(one_sided), Miner(), Request({20, 20, 0}, {30, 20}, 0.0), {}, {});
  EXPECT_EQ(one.plan.reason.rfind("no entry wall found on the left: 0 of ", 0), 0u) << one.plan.reason;
}

TEST(AdvancePlanner, AFaceTooObliqueForTheCutterIsRefused) {
  Entry entry{6.5};
  entry.face_angle = DegToRad(40.0);
  const AdvanceResult r = PlanAdvance(TaskMapFromSegments(entry.Walls()), Miner(),
                                      Request({entry.length - 22.0, 0, 0}, {entry.length - 6.0, 0}, 0.0), {}, {});
  EXPECT_EQ(r.plan.status, PlanStatus::kFailed);
  EXPECT_NE(r.plan.reason.find("off square to the entry (the cutter squares up to at most 34.4 deg)"),
            std::string::npos)
      << r.plan.reason;
}

TEST(AdvancePlanner, AGoalThePathPlannerCannotReachFailsThePlanWithItsReason) {
  // The vehicle stands in a room of its own beside the entry: no way into the entry.
  Entry entry{6.5};
  std::vector<Segment> walls = entry.Walls();
  for (const Segment& s : JitteredPolygon({{0, 25}, {40, 25}, {40, 45}, {0, 45}}, 1.0, 0.0, 1)) walls.push_back(s);
  const AdvanceResult r =
      PlanAdvance(TaskMapFromSegments(walls), Miner(), Request({20, 35, 0}, {entry.length - 4.0, 0}, 0.0), {}, {});
  EXPECT_EQ(r.plan.status, PlanStatus::kFailed);
  EXPECT_EQ(r.plan.reason.rfind("move into position for the box cut: goal (", 0), 0u) << r.plan.reason;
  EXPECT_NE(r.plan.reason.find("is not reachable from (20.00, 35.00, 0.00): no_path: "), std::string::npos)
      << r.plan.reason;
  ASSERT_EQ(r.maneuvers.size(), 1u);
  // An entry the vehicle does not fit in with the clearance: refused the same way.
  Entry tight{3.45};
  const AdvanceResult t = PlanAdvance(TaskMapFromSegments(tight.Walls()), Miner(),
                                      Request({tight.length - 20, 0, 0}, {tight.length - 4.0, 0}, 0.0), {}, {});
  EXPECT_EQ(t.plan.status, PlanStatus::kFailed);
  EXPECT_NE(t.plan.reason.find("move into position for the box cut"), std::string::npos) << t.plan.reason;
}

// The miner stopped short beside the entry's rib, its side 4 cm from it (the map grew around
// it, the CI mission of 2026-12-03 failed so): the advance is still planned, its first maneuver
// leaving with the clearance the miner has, never in contact with the walls; the others keep
// the request's clearance; the reason says so. A miner that touches the rib is refused.
TEST(AdvancePlanner, AVehicleWithinTheClearanceOfARibLeavesWithTheClearanceItHas) {
  Entry entry{6.5};
  entry.jitter = 0.0;
  const std::vector<Segment> walls = entry.Walls();
  const double half_width = 0.5 * 3.3;  // Miner()
  const Pose2 vehicle(entry.length - 20.0, 0.5 * entry.width - half_width - 0.04, 0.0);
  ASSERT_NEAR(testing::PoseClearance(walls, Miner().vertices, vehicle), 0.04, 1e-9);
  const AdvanceRequest request = Request(vehicle, {entry.length - 4.0, 0}, 0.0);
  const AdvanceResult r = PlanAdvance(TaskMapFromSegments(walls), Miner(), request, {}, {});
  ASSERT_EQ(r.plan.status, PlanStatus::kOk) << r.plan.reason;
  ASSERT_TRUE(r.leaving_clearance.has_value());
  EXPECT_GE(*r.leaving_clearance, 0.0);
  EXPECT_LT(*r.leaving_clearance, 0.04);
  EXPECT_NE(r.plan.reason.find("(the vehicle stood within 0.10 m of a wall: its first maneuver keeps "),
            std::string::npos)
      << r.plan.reason;
  ASSERT_GE(r.maneuvers.size(), 3u);
  for (size_t k = 0; k < r.maneuvers.size(); ++k) {
    const ManeuverCheck& m = r.maneuvers[k];
    ASSERT_EQ(m.result.status, SearchStatus::kFound) << m.result.reason;
    const double keep = k == 0 ? *r.leaving_clearance : request.clearance;
    const auto report = testing::CheckPath(walls, m.start, planner_test::AsChecked(m.result.path),
                                           planner_test::CheckSettings(Miner().vertices, keep));
    EXPECT_TRUE(report.ok) << "maneuver " << k << ": " << report.problem;
  }
  EXPECT_EQ(r.maneuvers.front().start.translation(), vehicle.translation());

  // Its side 2 cm into the rib: in contact, refused.
  const Pose2 touching(vehicle.x, vehicle.y + 0.06, 0.0);
  const AdvanceResult t =
      PlanAdvance(TaskMapFromSegments(walls), Miner(), Request(touching, {entry.length - 4.0, 0}, 0.0), {}, {});
  EXPECT_EQ(t.plan.status, PlanStatus::kFailed);
  EXPECT_FALSE(t.leaving_clearance.has_value());
  EXPECT_NE(t.plan.reason.find("is in collision"), std::string::npos) << t.plan.reason;
}

TEST(AdvancePlanner, ARibHuggingBoxCutInADeadEndLeavesNoRoomToReposition) {
  // With 0.1 m beyond the clearance at the rib (0.2 m to spare) the miner cannot turn a
  // heading bin (its far end swings 0.44 m for 5 degrees): it can only back straight out, and
  // a dead end 40 m long and 6.5 m wide has nowhere to shift sideways. The path planner's
  // answer is the reason.
  Entry entry{6.5};
  entry.dead_end = true;
  AdvanceOptions hugging;
  hugging.side_margin = 0.1;
  const AdvanceResult r = PlanAdvance(TaskMapFromSegments(entry.Walls()), Miner(),
                                      Request({entry.length - 22.0, 0, 0}, {entry.length - 4.0, 0}, 0.0), hugging, {});
  EXPECT_EQ(r.plan.status, PlanStatus::kFailed);
  EXPECT_EQ(r.plan.reason.rfind("reposition for slab cut 1: goal (", 0), 0u) << r.plan.reason;
  EXPECT_NE(r.plan.reason.find("is not reachable from ("), std::string::npos) << r.plan.reason;
  EXPECT_EQ(r.maneuvers.size(), 2u);
  // With the default margin (0.45 m: room to turn a bin) it can, at the cost of width (the
  // plans of the tests above have that margin); with a crosscut behind the face even hugging
  // the rib works (the vehicle turns with its rear in the crossing).
  const AdvanceResult wide = PlanAdvance(TaskMapFromSegments(entry.Walls()), Miner(),
                                         Request({entry.length - 22.0, 0, 0}, {entry.length - 4.0, 0}, 0.0), {}, {});
  EXPECT_EQ(wide.plan.status, PlanStatus::kOk) << wide.plan.reason;
  Entry with_crosscut{6.5};
  const AdvanceResult hug =
      PlanAdvance(TaskMapFromSegments(with_crosscut.Walls()), Miner(),
                  Request({with_crosscut.length - 22.0, 0, 0}, {with_crosscut.length - 4.0, 0}, 0.0), hugging, {});
  EXPECT_EQ(hug.plan.status, PlanStatus::kOk) << hug.plan.reason;
}

TEST(AdvancePlanner, BadRequestsAndOptionsAreRefusedInOneLine) {
  Entry entry{6.0};
  const TaskMap map = TaskMapFromSegments(entry.Walls());
  EXPECT_EQ(PlanAdvance(map, Miner(), Request({20, 0, 0}, {36, 0}, 0.0, 0.0), {}, {}).plan.reason,
            "depth 0.00 m is not in (0, 10.00] (max_depth)");
  EXPECT_EQ(PlanAdvance(map, Miner(), Request({20, 0, 0}, {36, 0}, 0.0, 11.0), {}, {}).plan.reason,
            "depth 11.00 m is not in (0, 10.00] (max_depth)");
  EXPECT_EQ(PlanAdvance(map, Miner(), Request({20, 0, 0}, {36, 0}, 0.0, 1.0, -1.0), {}, {}).plan.reason,
            "clearance -1.00 m is not >= 0");
  EXPECT_EQ(PlanAdvance(map, Miner(), Request({std::nan(""), 0, 0}, {36, 0}, 0.0), {}, {}).plan.reason,
            "the vehicle pose is not finite");
  AdvanceOptions bad;
  bad.box_cut_side = "middle";
  EXPECT_EQ(PlanAdvance(map, Miner(), Request({20, 0, 0}, {36, 0}, 0.0), bad, {}).plan.reason,
            "bad options: box_cut_side must be right or left");
  EXPECT_EQ(PlanAdvance(TaskMap{}, Miner(), Request({20, 0, 0}, {36, 0}, 0.0), {}, {}).plan.reason,
            "the map has no walls");
  // The box cut on the left instead.
  AdvanceOptions left;
  left.box_cut_side = "left";
  const AdvanceResult l = PlanAdvance(map, Miner(), Request({entry.length - 22, 0, 0}, {36, 0}, 0.0), left, {});
  ASSERT_EQ(l.plan.status, PlanStatus::kOk) << l.plan.reason;
  EXPECT_GT(l.plan.tasks[1].target.y, 0.5);
  EXPECT_LT(l.plan.tasks[3].target.y, -0.5);
}

}  // namespace
}  // namespace minenav
