#include "planner/contour_free_space.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <vector>

#include "common/geometry.h"
#include "mapper/contour_map_io.h"
#include "mapper/contour_mapper.h"
#include "planner/footprint.h"
#include "planner/se2_planner.h"
#include "planner/testing/path_checker.h"
#include "sim/mine_generator.h"
#include "sim/survey.h"

namespace minenav {
namespace {

mapper::Contour Open(std::vector<Eigen::Vector2d> points) {
  mapper::Contour c;
  c.points = std::move(points);
  return c;
}

bool HasFrontier(const ContourFreeSpace& s, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  for (const Segment& f : s.frontiers)
    if ((f.a - a).norm() < 1e-9 && (f.b - b).norm() < 1e-9) return true;
  return false;
}

TEST(ContourFreeSpace, AGapInARoomIsClosedByAFrontierAndBehindItIsUnknown) {
  // A 10 m room seen from inside (counter-clockwise), its south-west corner not seen.
  const ContourFreeSpace s = MakeContourFreeSpace({Open({{2, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 2}})});
  EXPECT_EQ(s.walls.size(), 4u);
  ASSERT_EQ(s.frontiers.size(), 1u);
  EXPECT_TRUE(HasFrontier(s, {0, 2}, {2, 0}));
  EXPECT_EQ(s.unclosed_ends, 0);
  EXPECT_EQ(s.Boundary(true).size(), 4u);
  EXPECT_EQ(s.Boundary(false).size(), 5u);
  const KnownFreeSpace known(s);
  EXPECT_TRUE(known.Contains({5, 5}));
  EXPECT_TRUE(known.Contains({1.2, 1.2}));   // just inside the frontier
  EXPECT_FALSE(known.Contains({0.5, 0.5}));  // the unseen corner behind it
  EXPECT_FALSE(known.Contains({11, 5}));
  EXPECT_FALSE(known.Contains({-3, -3}));
  EXPECT_FALSE(known.Contains({std::nan(""), 0}));
}

TEST(ContourFreeSpace, AShadowBehindAPillarIsCutOffAlongTheShadowRays) {
  // Sensor at the origin in a 20 m room; a pillar (4..6, -1..1) hides part of the east wall.
  // Seen: the pillar's west face (clockwise about the pillar), and the room wall in two
  // pieces around the shadow (bearings about +-14 deg to +-11 deg at x = 10).
  const double yshadow = 10.0 * 1.0 / 4.0;  // the shadow's edge on x = 10: rays through (4, +-1)
  const ContourFreeSpace s = MakeContourFreeSpace({
      Open({{10, yshadow}, {10, 10}, {-10, 10}, {-10, -10}, {10, -10}, {10, -yshadow}}),  // the room
      Open({{4, -1}, {4, 1}}),                                                               // the pillar's face
  });
  // Room end (10, -2.5) -> pillar start (4, -1) inward along the ray; pillar end (4, 1) ->
  // room start (10, 2.5) outward along the other ray.
  ASSERT_EQ(s.frontiers.size(), 2u);
  EXPECT_TRUE(HasFrontier(s, {10, -yshadow}, {4, -1}));
  EXPECT_TRUE(HasFrontier(s, {4, 1}, {10, yshadow}));
  EXPECT_EQ(s.unclosed_ends, 0);
  const KnownFreeSpace known(s);
  EXPECT_TRUE(known.Contains({2, 0}));
  EXPECT_TRUE(known.Contains({8, 5}));
  EXPECT_FALSE(known.Contains({8, 0}));  // in the shadow
  EXPECT_FALSE(known.Contains({5, 0}));  // in the pillar
}

TEST(ContourFreeSpace, AStartWhoseFreeSideFacesAwayDoesNotContinueAnEnd) {
  // A wall east along y = 0 (free north). Nearest start (12, 0): a contour that turns straight
  // back along the frontier (its free side is south of the frontier): refused. The next,
  // (14, 0) going on east, continues it.
  const ContourFreeSpace s = MakeContourFreeSpace({
      Open({{0, 0}, {10, 0}}),
      Open({{12, 0.3}, {11, 0.3}}),
      Open({{14, 0}, {20, 0}}),
  });
  EXPECT_TRUE(HasFrontier(s, {10, 0}, {14, 0}));
  EXPECT_FALSE(HasFrontier(s, {10, 0}, {12, 0.3}));
  // With no limit on the interior angle the nearest start wins.
  FreeSpaceOptions loose;
  loose.min_interior_angle_deg = 0.0;
  EXPECT_TRUE(HasFrontier(MakeContourFreeSpace({Open({{0, 0}, {10, 0}}), Open({{12, 0.3}, {11, 0.3}}),
                                                Open({{14, 0}, {20, 0}})},
                                               loose),
                          {10, 0}, {12, 0.3}));
}

TEST(ContourFreeSpace, AFrontierNeverCrossesAWall) {
  // A wall east along y = 0 (free north) ends at (10, 0); the nearest start, (12, 0), lies
  // behind a pillar (closed, clockwise): the frontier goes to (10, 4), the start of the wall
  // across the entry, instead.
  mapper::Contour pillar;
  pillar.closed = true;
  pillar.points = {{10.5, -1}, {10.5, 1}, {11.5, 1}, {11.5, -1}};
  const ContourFreeSpace s = MakeContourFreeSpace({
      Open({{0, 0}, {10, 0}}),
      pillar,
      Open({{12, 0}, {20, 0}}),
      Open({{10, 4}, {0, 4}}),
  });
  EXPECT_TRUE(HasFrontier(s, {10, 0}, {10, 4}));
  EXPECT_FALSE(HasFrontier(s, {10, 0}, {12, 0}));
  for (const Segment& f : s.frontiers)
    for (const Segment& w : s.walls) {
      const auto x = SegmentIntersection(f, w);
      if (x) {
        EXPECT_TRUE((*x - f.a).norm() < 1e-6 || (*x - f.b).norm() < 1e-6) << "frontier crosses a wall";
      }
    }
}

TEST(ContourFreeSpace, ClosedContoursHaveNoEndsAndBadOptionsAreNamed) {
  mapper::Contour pillar;
  pillar.closed = true;
  pillar.points = {{0, 0}, {0, 2}, {2, 2}, {2, 0}};
  const ContourFreeSpace s = MakeContourFreeSpace({pillar, Open({{5, 5}})});
  EXPECT_EQ(s.walls.size(), 4u);
  EXPECT_TRUE(s.frontiers.empty());
  EXPECT_EQ(s.open_contours, 0);
  EXPECT_FALSE(KnownFreeSpace(s).Contains({1, 1}));
  EXPECT_FALSE(KnownFreeSpace(ContourFreeSpace{}).Contains({1, 1}));
  FreeSpaceOptions bad;
  bad.probe_rays = 0;
  EXPECT_NE(ValidateOptions(bad).find("probe_rays"), std::string::npos);
  EXPECT_EQ(ValidateOptions(FreeSpaceOptions{}), "");
}

// ---- a real contour map: the mapper on a simulated survey of the synthetic mine ----

// Crossings of a ray from p with the true world's walls: odd = inside the panel and outside
// every pillar (the mine's walls are closed polygons).
bool InTrueFreeSpace(const std::vector<Segment>& world, const Eigen::Vector2d& p) {
  int crossings = 0;
  for (const Segment& s : world) {
    if ((s.a.y() > p.y()) == (s.b.y() > p.y())) continue;
    const double x = s.a.x() + (p.y() - s.a.y()) * (s.b.x() - s.a.x()) / (s.b.y() - s.a.y());
    if (x > p.x()) ++crossings;
  }
  return crossings % 2 == 1;
}

double DistanceToWorld(const std::vector<Segment>& world, const Eigen::Vector2d& p) {
  double d = 1e9;
  for (const Segment& s : world) d = std::min(d, PointToSegmentDistance(p, s));
  return d;
}

struct SurveyedMine {
  std::vector<Segment> world;
  std::vector<Station> stations;  // all of the survey's
  int surveyed = 0;               // the first `surveyed` were scanned and mapped
  std::vector<mapper::Contour> contours;
};

const SurveyedMine& Mine() {
  static const SurveyedMine mine = [] {
    SurveyedMine m;
    MineOptions options;  // 2 x 3 pillars of 12 m, 6 m entries
    m.world = GenerateRoomAndPillarMine(options);
    m.stations = MineSurveyStations(options, 42);
    m.surveyed = 8;  // along the first entry only
    const std::vector<Station> first(m.stations.begin(), m.stations.begin() + m.surveyed);
    SurveyOptions survey;
    survey.sensor.max_range = 20.0;  // m: leaves most of the panel unseen
    mapper::ContourMapper mapper;
    RunSurvey({m.world}, first, survey, [&](const SurveyRecord& r) {
      const mapper::InsertResult ins = mapper.InsertScan(r.scan, r.estimate);
      EXPECT_TRUE(ins.accepted) << ins.reason;
    });
    for (const auto& [id, c] : mapper.map().contours()) m.contours.push_back(c);
    if (const char* dump = std::getenv("MINENAV_DUMP_SURVEY_MAP")) mapper::SaveContourMapJson(dump, mapper.map());
    return m;
  }();
  return mine;
}

testing::PathCheckSettings Checker(const Footprint& fp, double clearance) {
  testing::PathCheckSettings s;
  s.polygon = fp.vertices;
  s.clearance = clearance;
  s.sample_step = 0.02;
  return s;
}

std::vector<testing::CheckedPiece> Pieces(const PlannedPath& path) {
  std::vector<testing::CheckedPiece> out;
  for (const MotionPiece& p : path.pieces) out.push_back({static_cast<int>(p.motion), p.end});
  return out;
}

TEST(ContourFreeSpaceOnASurvey, KnownFreeSpaceIsTrulyFreeAndHoldsTheStations) {
  const SurveyedMine& m = Mine();
  const ContourFreeSpace s = MakeContourFreeSpace(m.contours);
  ASSERT_GT(s.walls.size(), 50u);
  EXPECT_GT(s.frontiers.size(), 0u);
  EXPECT_EQ(s.unclosed_ends, 0);
  const KnownFreeSpace known(s);
  for (int k = 0; k < m.surveyed; ++k) EXPECT_TRUE(known.Contains(m.stations[static_cast<size_t>(k)].pose.translation())) << k;
  // Every point of a 0.5 m grid that the map calls known free is truly free (away from the walls
  // by more than the map's error), and a good part of the true free space near the stations is known.
  int known_points = 0, wrong = 0;
  for (double x = -5; x <= 70; x += 0.5)
    for (double y = -5; y <= 50; y += 0.5) {
      const Eigen::Vector2d p(x, y);
      if (!known.Contains(p)) continue;
      ++known_points;
      if (!InTrueFreeSpace(m.world, p) && DistanceToWorld(m.world, p) > 0.3) ++wrong;
    }
  EXPECT_GT(known_points, 1000);  // > 250 m^2
  EXPECT_EQ(wrong, 0);
  // The far end of the serpentine was never seen.
  EXPECT_FALSE(known.Contains(m.stations.back().pose.translation()));
}

TEST(ContourFreeSpaceOnASurvey, APathStaysInSeenFreeSpaceAndAGoalBehindAFrontierIsRefused) {
  const SurveyedMine& m = Mine();
  const ContourFreeSpace s = MakeContourFreeSpace(m.contours);
  const KnownFreeSpace known(s);
  const Footprint miner = Footprint::Rectangle(3.3, 10.0);
  Se2PlannerOptions options;
  options.clearance = 0.15;
  const Se2Planner planner(s.Boundary(false), miner, options);
  // Between two surveyed stations along the entry, heading along it.
  const Pose2 start(m.stations[1].pose.x, m.stations[1].pose.y, 0.0);
  const Pose2 goal(m.stations[6].pose.x, m.stations[6].pose.y, 0.0);
  const Se2PlanResult r = planner.Plan(start, goal);
  ASSERT_EQ(r.status, SearchStatus::kFound) << r.reason;
  // Never across a frontier (the frontiers alone as the map, no contact), and clear of the
  // TRUE walls (the map's error is a few cm; the request kept 15 cm, the check asks for 5).
  const testing::PathCheckReport on_frontiers = testing::CheckPath(s.frontiers, r.path.start, Pieces(r.path), Checker(miner, 0.1));
  EXPECT_TRUE(on_frontiers.ok) << on_frontiers.problem;
  const testing::PathCheckReport on_world = testing::CheckPath(m.world, r.path.start, Pieces(r.path), Checker(miner, 0.05));
  EXPECT_TRUE(on_world.ok) << on_world.problem;
  EXPECT_TRUE(InTrueFreeSpace(m.world, start.translation()));

  // A goal in true free space behind a frontier: inside the map's box, free of the walls, not
  // known. A small vehicle (1 x 1.5 m), so that exploration can get there at all (the miner
  // cannot turn out of the entry into a crosscut in a few thousand expansions).
  const Footprint small = Footprint::Rectangle(1.0, 1.5);
  const Se2Planner explorer(s.Boundary(true), small, options);
  const Se2Planner careful(s.Boundary(false), small, options);
  std::optional<Pose2> behind;
  SearchLimits quick;
  quick.max_expansions = 20000;
  int tried = 0;
  for (double x = 0; x <= 70 && !behind && tried < 30; x += 1.0)
    for (double y = 0; y <= 50 && !behind && tried < 30; y += 1.0) {
      const Pose2 p(x, y, 0.0);
      if (known.Contains(p.translation()) || !InTrueFreeSpace(m.world, p.translation()) ||
          DistanceToWorld(m.world, p.translation()) < 2.5 || DistanceToWorld(s.frontiers, p.translation()) < 2.0 ||
          !explorer.PoseFree(p) || !careful.PoseFree(p))
        continue;
      ++tried;
      const Se2PlanResult explored = explorer.Plan(start, p, quick);
      if (explored.status != SearchStatus::kFound) continue;
      behind = p;
      // Exploration's path is clear of the true walls too, and it does cross a frontier.
      EXPECT_TRUE(testing::CheckPath(m.world, explored.path.start, Pieces(explored.path), Checker(small, 0.05)).ok);
      const auto crossing = testing::CheckPath(s.frontiers, explored.path.start, Pieces(explored.path), Checker(small, 0.0));
      EXPECT_LT(crossing.min_clearance, 1e-9) << "exploration reached " << p << " without crossing a frontier";
    }
  ASSERT_TRUE(behind.has_value()) << "no goal behind a frontier that exploration reaches";
  const Se2PlanResult refused = careful.Plan(start, *behind, quick);
  EXPECT_EQ(refused.status, SearchStatus::kNoPath) << "to " << *behind << ": " << refused.reason;
  EXPECT_FALSE(known.Contains(behind->translation()));
}

}  // namespace
}  // namespace minenav
