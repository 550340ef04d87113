// The next scan station of a survey (survey_planner.h) on contour maps the mapper makes from
// simulated scans of generated mines: the station is reachable (its path judged by the
// independent checker against the TRUE walls and never across a frontier), in known and truly
// free space, before an open frontier, and the scan taken there truly overlaps the map by at
// least the bound; a small world scanned whole ends COMPLETE; a frontier the vehicle cannot
// reach ends COMPLETE and says why; and an exploration from one scan, station after station,
// covers a generated mine of 1 x 2 pillars.

#include "planner/survey_planner.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <vector>

#include "common/angle.h"
#include "common/file_io.h"
#include "mapper/contour_mapper.h"
#include "planner/contour_free_space.h"
#include "planner/task_plan_svg.h"
#include "planner/testing/path_checker.h"
#include "sensor_driver/ladar_simulator.h"
#include "sim/mine_generator.h"
#include "sim/world.h"

namespace minenav {
namespace {

constexpr int64_t kT0 = 1'000'000'000'000'000;

// A compact ladar carrier (the demo's survey vehicle): it turns anywhere in a 6 m entry.
Footprint Carrier() { return Footprint::Rectangle(1.2, 2.0); }

// The true world and the mapper that maps it from simulated scans at true poses.
struct Exploration {
  explicit Exploration(std::vector<Segment> walls, double range = 15.0)
      : world(walls), index(walls), truth(std::move(walls)), simulator(Model(range), 7) {}
  static LadarModel Model(double range) {
    LadarModel m = LadarModel::Typhoon();
    m.max_range = range;
    return m;
  }
  // A scan at the true pose, inserted with the true pose as its initial estimate.
  void ScanAt(const Pose2& pose) {
    const LadarScan scan = simulator.Simulate(index, pose, Pose2(), kT0 + scans * 1'000'000, scans);
    const mapper::InsertResult r = mapper.InsertScan(scan, pose);
    EXPECT_TRUE(r.accepted) << r.reason;
    ++scans;
  }
  TaskMap Map() const {
    std::vector<mapper::Contour> contours;
    for (const auto& [id, c] : mapper.map().contours()) contours.push_back(c);
    return TaskMapFromContours(contours);
  }
  // Fraction of a true scan from `pose` whose points lie within 0.3 m of `map`'s walls: how
  // much of what the ladar would really see there the map already holds.
  double TrueOverlap(const TaskMap& map, const Pose2& pose) const {
    const LadarScan scan = simulator.Simulate(index, pose, Pose2(), kT0, 999);
    const StaticSegmentIndex walls(map.walls);
    int valid = 0, on_map = 0;
    for (const Eigen::Vector2d& p : ScanPointsInWorld(scan, pose)) {
      ++valid;
      bool near = false;
      walls.ForEachNear(p, 0.3, [&](int i) { near = near || PointToSegmentDistance(p, map.walls[static_cast<size_t>(i)]) < 0.3; });
      on_map += near ? 1 : 0;
    }
    return valid > 0 ? static_cast<double>(on_map) / valid : 0.0;
  }

  World world;
  StaticSegmentIndex index;
  std::vector<Segment> truth;
  LadarSimulator simulator;
  mapper::ContourMapper mapper;
  int64_t scans = 0;
};

testing::PathCheckSettings Settings(const Footprint& f, double clearance) {
  testing::PathCheckSettings s;
  s.polygon = f.vertices;
  s.clearance = clearance;
  s.sample_step = 0.02;
  return s;
}

std::vector<testing::CheckedPiece> Pieces(const PlannedPath& path) {
  std::vector<testing::CheckedPiece> out;
  for (const MotionPiece& p : path.pieces) out.push_back({static_cast<int>(p.motion), p.end});
  return out;
}

SurveyPlannerOptions Options(double range) {
  SurveyPlannerOptions o;
  o.sensor_range = range;
  return o;
}

MineOptions SmallMine() {
  MineOptions m;
  m.pillar_rows = 1;
  m.pillar_cols = 2;  // a panel of 42 x 24 m, 720 m^2 free
  return m;
}

// Everything a chosen station must be, against the truth.
void ExpectGoodStation(const Exploration& e, const TaskMap& map, const Footprint& footprint, const SurveyRequest& request,
                       const SurveyDecision& d, const SurveyPlannerOptions& options) {
  ASSERT_EQ(d.plan.status, PlanStatus::kOk) << d.plan.reason;
  ASSERT_EQ(d.plan.tasks.size(), 1u);
  const Task& t = d.plan.tasks[0];
  EXPECT_EQ(t.kind, TaskKind::kScanStation);
  EXPECT_EQ(t.appendages, Appendages::kStowed);
  EXPECT_EQ(t.depends_on, -1);
  ASSERT_TRUE(d.chosen.has_value());
  const Eigen::Vector2d p = t.target.translation();
  // In the known free space, and truly free.
  EXPECT_TRUE(KnownFreeSpace(map.AsFreeSpace()).Contains(p));
  EXPECT_TRUE(e.world.SameSpace(p, request.vehicle.translation()));
  // Before an open frontier (within max_standoff of its middle, in sight), or at an intersection.
  const StationCandidate& c = d.candidates[*d.chosen];
  if (c.frontier >= 0) {
    const Segment& f = d.frontiers[static_cast<size_t>(c.frontier)].segment;
    EXPECT_LE((0.5 * (f.a + f.b) - p).norm(), options.max_standoff + 1e-9);
    EXPECT_TRUE(d.frontiers[static_cast<size_t>(c.frontier)].dropped.empty());
  }
  // The scan there would truly overlap the map by the bound.
  EXPECT_GE(e.TrueOverlap(map, t.target), options.min_overlap) << t.description;
  // Reachable: the path starts at the vehicle, ends at the station, is clear of the TRUE walls
  // (the request kept 0.1 m from the map; the map is a few cm off) and crosses no frontier.
  ASSERT_FALSE(d.path.pieces.empty());
  EXPECT_LT((d.path.pieces.back().end.translation() - p).norm(), 1e-6);
  const auto on_world = testing::CheckPath(e.truth, request.vehicle, Pieces(d.path), Settings(footprint, 0.03));
  EXPECT_TRUE(on_world.ok) << on_world.problem;
  if (!map.frontiers.empty()) {
    const auto on_frontiers = testing::CheckPath(map.frontiers, request.vehicle, Pieces(d.path), Settings(footprint, 0.0));
    EXPECT_TRUE(on_frontiers.ok) << on_frontiers.problem;
  }
}

TEST(SurveyPlanner, OnAPartialMapTheStationIsReachableKnownFreeBeforeAFrontierAndOverlaps) {
  Exploration e(GenerateRoomAndPillarMine(SmallMine()));
  const Pose2 start(3.0, 3.0, 0.0);
  e.ScanAt(start);
  e.ScanAt({9.0, 3.0, 0.0});
  const TaskMap map = e.Map();
  ASSERT_GT(map.frontiers.size(), 0u);
  SurveyRequest request;
  request.vehicle = Pose2(9.0, 3.0, 0.0);
  request.clearance = 0.1;
  request.visited = {start};
  const SurveyPlannerOptions options = Options(15.0);
  const SurveyDecision d = PlanNextStation(map, Carrier(), request, options, {});
  ExpectGoodStation(e, map, Carrier(), request, d, options);
  std::printf("%s\n", d.plan.reason.c_str());
  // The miner too, from the same place (in a 6 m entry it cannot turn: it goes on straight).
  const SurveyDecision m = PlanNextStation(map, Footprint::Rectangle(3.3, 10.0), request, options, {});
  ExpectGoodStation(e, map, Footprint::Rectangle(3.3, 10.0), request, m, options);
  std::printf("miner: %s\n", m.plan.reason.c_str());
}

TEST(SurveyPlanner, ASmallWorldScannedWholeIsComplete) {
  // A room of 24 x 14 m with a pillar in it, seen whole from two stations at opposite
  // corners of the pillar (from its side, level with it, its top and bottom are edge-on:
  // they would stay unseen, behind frontiers).
  Exploration e({{0, 0, 24, 0}, {24, 0, 24, 14}, {24, 14, 0, 14}, {0, 14, 0, 0},  // counter-clockwise: seen from inside
                 {10, 5, 10, 9}, {10, 9, 14, 9}, {14, 9, 14, 5}, {14, 5, 10, 5}});
  e.ScanAt({4.0, 3.0, 0.0});
  e.ScanAt({20.0, 3.0, 0.0});
  e.ScanAt({20.0, 11.0, 0.0});
  const TaskMap map = e.Map();
  SurveyRequest request;
  request.vehicle = Pose2(20.0, 11.0, 0.0);
  request.clearance = 0.1;
  request.visited = {Pose2(4.0, 3.0, 0.0), Pose2(20.0, 3.0, 0.0)};
  const SurveyDecision d = PlanNextStation(map, Carrier(), request, Options(15.0), {});
  EXPECT_EQ(d.plan.status, PlanStatus::kComplete) << d.plan.reason;
  EXPECT_TRUE(d.plan.tasks.empty());
  EXPECT_EQ(d.plan.reason.rfind("no frontier left: the known free space is closed", 0), 0u) << d.plan.reason;
}

TEST(SurveyPlanner, AFrontierTheVehicleCannotReachEndsTheSurveyAndSaysWhy) {
  // Hand-made contour map (free space on the left of every wall): room A (the vehicle) joins
  // room B through a doorway 1 m wide; room B opens into unknown space through a frontier.
  TaskMap map;
  map.oriented = true;
  map.walls = {{0, 0, 20, 0},   {20, 0, 20, 4.5}, {20, 4.5, 20, 4.5}, {20, 5.5, 20, 10}, {20, 10, 0, 10},
               {0, 10, 0, 0},                                                     // room A, door at x = 20
               {20, 4.5, 21, 4.5}, {21, 4.5, 21, 0}, {21, 0, 40, 0}, {40, 0, 40, 3},  // room B below the door
               {40, 7, 40, 10}, {40, 10, 21, 10}, {21, 10, 21, 5.5}, {21, 5.5, 20, 5.5}};
  map.walls.erase(map.walls.begin() + 2);  // the zero-length piece
  map.frontiers = {{40, 3, 40, 7}};         // room B's east side, not seen yet
  SurveyRequest request;
  request.vehicle = Pose2(5.0, 5.0, 0.0);
  request.clearance = 0.1;
  const SurveyDecision d = PlanNextStation(map, Carrier(), request, Options(15.0), {});
  EXPECT_EQ(d.plan.status, PlanStatus::kComplete) << d.plan.reason;
  EXPECT_EQ(d.plan.reason.rfind("no reachable frontier: 1 frontier left, none reachable: frontier 0 (4.0 m at (40.0, 5.0)) ", 0),
            0u)
      << d.plan.reason;
  EXPECT_NE(d.plan.reason.find("not reachable (no_path)"), std::string::npos) << d.plan.reason;
  // A frontier seen from a station close by and still open is a gap: dropped, and said so.
  request.vehicle = Pose2(37.0, 5.0, 0.0);
  const SurveyDecision near = PlanNextStation(map, Carrier(), request, Options(15.0), {});
  EXPECT_EQ(near.plan.status, PlanStatus::kComplete) << near.plan.reason;
  EXPECT_NE(near.plan.reason.find("seen from the station at (37.0, 5.0) 3.0 m away and still open"), std::string::npos)
      << near.plan.reason;
}

TEST(SurveyPlanner, BadRequestsAreRefusedInOneLine) {
  TaskMap lines = TaskMapFromSegments({{0, 0, 10, 0}});
  SurveyRequest request;
  request.vehicle = Pose2(5, 5, 0);
  EXPECT_EQ(PlanNextStation(lines, Carrier(), request, {}, {}).plan.reason,
            "a survey needs a contour map (its frontiers), not a line map");
  TaskMap empty;
  empty.oriented = true;
  EXPECT_EQ(PlanNextStation(empty, Carrier(), request, {}, {}).plan.reason, "the map has no walls yet");
  SurveyPlannerOptions bad;
  bad.min_overlap = 1.5;
  EXPECT_EQ(PlanNextStation(empty, Carrier(), request, bad, {}).plan.reason, "bad options: min_overlap must be in [0, 1]");
  request.vehicle.x = std::nan("");
  EXPECT_EQ(PlanNextStation(empty, Carrier(), request, {}, {}).plan.reason, "the vehicle pose is not finite");
}

TEST(SurveyPlanner, ExploringASmallMineStationByStationCoversIt) {
  const MineOptions mine = SmallMine();
  Exploration e(GenerateRoomAndPillarMine(mine));
  const SurveyPlannerOptions options = Options(15.0);
  SurveyRequest request;
  request.vehicle = Pose2(3.0, 3.0, 0.0);
  request.clearance = 0.1;
  e.ScanAt(request.vehicle);
  int stations = 1;
  double decision_ms_max = 0.0, decision_ms_total = 0.0;
  SurveyDecision d;
  for (int round = 0; round < 25; ++round) {
    const TaskMap map = e.Map();
    const auto t0 = std::chrono::steady_clock::now();
    d = PlanNextStation(map, Carrier(), request, options, {});
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    decision_ms_max = std::max(decision_ms_max, ms);
    decision_ms_total += ms;
    // MINENAV_DUMP_SURVEY_SVG=PREFIX: a picture of each decision over the true walls.
    if (const char* dump = std::getenv("MINENAV_DUMP_SURVEY_SVG")) {
      SvgScene scene = SurveyScene(map, Carrier(), request, d, "decision " + std::to_string(round + 1));
      scene.lines.insert(scene.lines.begin(), SvgLineLayer{"true walls", "#bbbbbb", 4.0, e.truth, {}});
      WriteFileAtomically(std::string(dump) + std::to_string(round + 1) + ".svg", RenderSvg(scene));
    }
    if (d.plan.status != PlanStatus::kOk) break;
    ExpectGoodStation(e, map, Carrier(), request, d, options);
    request.visited.push_back(request.vehicle);
    request.vehicle = d.plan.tasks[0].target;
    e.ScanAt(request.vehicle);
    ++stations;
  }
  EXPECT_EQ(d.plan.status, PlanStatus::kComplete) << d.plan.reason;
  // Explored: the known free space against the true free space, on a 0.25 m grid.
  const TaskMap map = e.Map();
  const KnownFreeSpace known(map.AsFreeSpace());
  const Eigen::Vector2d panel = MinePanelSize(mine);
  const Eigen::Vector2d inside(3.0, 3.0);
  int truly_free = 0, known_free = 0, known_not_free = 0;
  for (double x = 0.125; x < panel.x(); x += 0.25)
    for (double y = 0.125; y < panel.y(); y += 0.25) {
      const Eigen::Vector2d p(x, y);
      const bool free = e.world.SameSpace(p, inside);
      const bool k = known.Contains(p);
      truly_free += free ? 1 : 0;
      known_free += (k && free) ? 1 : 0;
      known_not_free += (k && !free) ? 1 : 0;
    }
  const double coverage = static_cast<double>(known_free) / truly_free;
  std::printf("explored %d stations: %.0f of %.0f m^2 truly free known free (%.1f %%), %.1f m^2 known but not free; "
              "decisions %.0f ms mean, %.0f ms max; %s\n",
              stations, known_free * 0.0625, truly_free * 0.0625, 100.0 * coverage, known_not_free * 0.0625,
              decision_ms_total / stations, decision_ms_max, d.plan.reason.c_str());
  EXPECT_GE(coverage, 0.95);
  EXPECT_LE(known_not_free * 0.0625, 10.0);  // the walls' own band: a few cm along ~250 m of walls
  EXPECT_LE(stations, 15);
}

}  // namespace
}  // namespace minenav
