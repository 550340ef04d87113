// The SE(2) planner: its motions and analytic shots, the footprint and its collision test
// against brute force, and planned paths judged by the independent checker
// (testing/path_checker.h) in a room, a corridor and the multi-point corner turn; every bad
// request gets a clear status and reason.

#include "planner/se2_planner.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "common/file_io.h"
#include "planner/analytic_shot.h"
#include "planner/grid_dijkstra.h"
#include "planner/test_maps.h"
#include "planner/testing/path_checker.h"

namespace minenav {
namespace {

using planner_test::AsChecked;

testing::PathCheckSettings CheckerFor(const Se2Planner& planner) {
  testing::PathCheckSettings s;
  s.polygon = planner.footprint().vertices;
  s.turn_radius = planner.options().turn_radius;
  s.clearance = planner.options().clearance;
  return s;
}

// Brute force: the independent checker at the one pose, and every vertex inside the map's box
// [-half, half]^2 (the map ends there).
bool BruteForceFree(const std::vector<Segment>& walls, const Pose2& p, const testing::PathCheckSettings& st,
                    double half) {
  for (const auto& v : st.polygon) {
    const Eigen::Vector2d w = p * v;
    if (std::abs(w.x()) > half || std::abs(w.y()) > half) return false;
  }
  return testing::CheckPath(walls, p, {}, st).ok;  // samples only the start pose
}

TEST(MotionTest, ArcsTurnAboutTheCentreOnTheirSide) {
  const double r = 4.0, quarter = r * kPi / 2;
  const Pose2 o(0, 0, 0);
  const Pose2 l = PoseAfter(o, Motion::kArcLeft, quarter, r);
  EXPECT_NEAR(l.x, 4.0, 1e-12);
  EXPECT_NEAR(l.y, 4.0, 1e-12);
  EXPECT_NEAR(l.theta, kPi / 2, 1e-12);
  const Pose2 rr = PoseAfter(o, Motion::kArcRight, quarter, r);
  EXPECT_NEAR(rr.y, -4.0, 1e-12);
  EXPECT_NEAR(rr.theta, -kPi / 2, 1e-12);
  // Reversing along the left circle: backwards, heading turning clockwise.
  const Pose2 lr = PoseAfter(o, Motion::kArcLeftReverse, quarter, r);
  EXPECT_NEAR(lr.x, -4.0, 1e-12);
  EXPECT_NEAR(lr.y, 4.0, 1e-12);
  EXPECT_NEAR(lr.theta, -kPi / 2, 1e-12);
  const Pose2 b = PoseAfter(o, Motion::kReverse, 2.0, r);
  EXPECT_NEAR(b.x, -2.0, 1e-12);
  const Pose2 t = PoseAfter(o, Motion::kTurnInPlace, -1.0, r);
  EXPECT_NEAR(t.theta, -1.0, 1e-12);
  EXPECT_EQ(t.x, 0.0);
}

TEST(MotionTest, ThePieceSamplerGivesPoseAftersPosesWithTheirCosineAndSine) {
  // Every motion, from starts in every quadrant, at amounts up to 200 m (and 7 rad turning):
  // the sampler's poses are PoseAfter's, its cosine and sine those of PoseAfter's heading.
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> coordinate(-500.0, 500.0), angle(-kPi, kPi), unit(0.0, 1.0);
  for (int motion = 0; motion < 7; ++motion)
    for (int trial = 0; trial < 200; ++trial) {
      const Motion m = static_cast<Motion>(motion);
      const Pose2 start(coordinate(rng), coordinate(rng), angle(rng));
      const double radius = m == Motion::kTurnInPlace || !IsArc(m) ? 0.0 : 1.0 + 9.0 * unit(rng);
      const double amount = m == Motion::kTurnInPlace ? 14.0 * (unit(rng) - 0.5) : 200.0 * unit(rng);
      const PieceSampler::Sample q = PieceSampler(start, m, radius).At(amount);
      const Pose2 want = PoseAfter(start, m, amount, radius);
      EXPECT_NEAR(q.pose.x, want.x, 1e-9) << ToString(m) << " " << amount;
      EXPECT_NEAR(q.pose.y, want.y, 1e-9) << ToString(m) << " " << amount;
      EXPECT_NEAR(NormalizeAngle(q.pose.theta - want.theta), 0.0, 1e-12) << ToString(m) << " " << amount;
      EXPECT_NEAR(q.cos_theta, std::cos(want.theta), 1e-12);
      EXPECT_NEAR(q.sin_theta, std::sin(want.theta), 1e-12);
    }
}

TEST(MotionTest, MergedPathsCountLengthAndReversals) {
  PlannedPath p;
  p.pieces = MergePieces({{Motion::kForward, 1.0, 0.0, {}},
                          {Motion::kForward, 2.0, 0.0, {}},
                          {Motion::kTurnInPlace, 0.5, 0.0, {}},
                          {Motion::kArcLeftReverse, 1.5, 4.0, {}},
                          {Motion::kArcLeft, 1.0, 4.0, {}}});
  ASSERT_EQ(p.pieces.size(), 4u);
  EXPECT_DOUBLE_EQ(p.pieces[0].amount, 3.0);
  EXPECT_DOUBLE_EQ(p.Length(), 5.5);
  EXPECT_EQ(p.Reversals(), 2);
  // Turns in place are merged only while under half a turn.
  const auto turns = MergePieces({{Motion::kTurnInPlace, 2.0, 0.0, {}}, {Motion::kTurnInPlace, 2.0, 0.0, {}}});
  EXPECT_EQ(turns.size(), 2u);
  Motion m;
  EXPECT_TRUE(MotionFromString("arc_right_reverse", m));
  EXPECT_EQ(m, Motion::kArcRightReverse);
  EXPECT_EQ(static_cast<int>(m), 6);  // path_segment_t.ARC_RIGHT_REVERSE
}

TEST(AnalyticShotTest, EveryShotIsAFeasiblePathToTheGoal) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-20, 20), a(-kPi, kPi);
  testing::PathCheckSettings st;
  st.polygon = {{0.1, 0.1}, {-0.1, 0.1}, {-0.1, -0.1}, {0.1, -0.1}};
  st.sample_step = 0.5;
  int csc = 0;
  for (int trial = 0; trial < 100; ++trial) {
    const Pose2 from(u(rng), u(rng), a(rng)), to(u(rng), u(rng), a(rng));
    const auto shots = AnalyticShots(from, to, 4.0, MotionCosts{});
    ASSERT_GE(shots.size(), 2u);  // the two turn-straight-turn shots always exist
    for (size_t k = 1; k < shots.size(); ++k) EXPECT_LE(shots[k - 1].cost, shots[k].cost);
    for (const AnalyticShot& s : shots) {
      PlannedPath p;
      p.start = from;
      p.pieces = s.pieces;
      const auto report = testing::CheckPath({}, from, AsChecked(p), st);
      EXPECT_TRUE(report.ok) << report.problem;
      EXPECT_NEAR(report.length, p.Length(), 1e-6);
      EXPECT_NEAR(TranslationDistance(s.pieces.back().end, to), 0.0, 1e-6);
      if (IsArc(s.pieces.front().motion)) ++csc;
    }
  }
  EXPECT_GT(csc, 300);  // the Dubins words exist for most pairs this far apart
}

TEST(AnalyticShotTest, TheCheapestShotCostIsTheCheapestShotsCost) {
  // The heuristic's cost-only shot against the built, traced and sorted shots: random pairs,
  // near pairs (loops, empty pieces) and the same position, after each previous direction.
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-20, 20), near(-1, 1), a(-kPi, kPi);
  MotionCosts costs;
  costs.turn_in_place_per_rad = 1.3;
  for (int trial = 0; trial < 600; ++trial) {
    const Pose2 from(u(rng), u(rng), a(rng));
    const Pose2 to = trial % 3 == 0   ? Pose2(u(rng), u(rng), a(rng))
                     : trial % 3 == 1 ? Pose2(from.x + near(rng), from.y + near(rng), a(rng))
                                      : Pose2(from.x, from.y, trial % 2 ? from.theta : a(rng));
    for (const int previous : {0, 1, -1}) {
      const auto shots = AnalyticShots(from, to, 4.0, costs, previous);
      ASSERT_FALSE(shots.empty());
      EXPECT_NEAR(CheapestShotCost(from, to, 4.0, costs, previous), shots.front().cost, 1e-9)
          << from << " -> " << to << " after " << previous;
    }
  }
}

TEST(AnalyticShotTest, ACandidatesCostIsThePieceCostOfTheShotItBuilds) {
  // The costs the planner orders its shots by, before building them, against PieceCost over
  // the built pieces; cheapest first; every word that exists is a candidate (the two
  // turn-straight-turn words always, the CSC words where the circles allow).
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-20, 20), a(-kPi, kPi);
  MotionCosts costs;
  costs.turn_in_place_per_rad = 2.0;
  costs.reverse_factor = 1.5;
  costs.direction_change = 3.0;
  int built = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Pose2 from(u(rng), u(rng), a(rng)), to(u(rng), u(rng), a(rng));
    for (const int previous : {0, 1, -1}) {
      const ShotCandidates candidates(from, to, 4.0, costs, previous);
      ASSERT_GE(candidates.size(), 2);
      ASSERT_LE(candidates.size(), 10);
      for (int i = 0; i < candidates.size(); ++i) {
        if (i > 0) {
          EXPECT_LE(candidates.cost(i - 1), candidates.cost(i));
        }
        const std::optional<AnalyticShot> shot = candidates.Build(i);
        if (!shot) continue;
        ++built;
        double cost = 0.0;
        int direction = previous;
        for (const MotionPiece& p : shot->pieces) {
          cost += PieceCost(p, direction, costs);
          if (DriveDirection(p.motion) != 0) direction = DriveDirection(p.motion);
        }
        EXPECT_NEAR(shot->cost, cost, 1e-9);
        EXPECT_NEAR(candidates.cost(i), cost, 1e-9) << from << " -> " << to << " candidate " << i;
        EXPECT_NEAR(TranslationDistance(shot->pieces.back().end, to), 0.0, 1e-6);
        EXPECT_NEAR(HeadingDistance(shot->pieces.back().end, to), 0.0, 1e-6);
      }
    }
  }
  EXPECT_GT(built, 300 * 3 * 6);  // most CSC words exist this far apart, and all are built
}

TEST(FootprintTest, RectangleRadiiAndValidation) {
  const Footprint f = Footprint::Rectangle(3.3, 10.0);
  EXPECT_NEAR(InscribedRadius(f), 1.65, 1e-12);
  EXPECT_NEAR(CircumscribedRadius(f), std::hypot(1.65, 5.0), 1e-12);
  EXPECT_EQ(ValidateFootprint(f), "");
  EXPECT_EQ(ValidateFootprint({{{0, 0}, {1, 0}}}), "footprint needs at least 3 vertices, has 2");
  EXPECT_EQ(ValidateFootprint({{{1, 1}, {2, 1}, {2, 2}}}),
            "footprint does not contain the vehicle's origin (the pose the planner plans for)");
  EXPECT_EQ(ValidateFootprint({{{1, 1}, {-1, -1}, {1, -1}, {-1, 1}}}), "footprint edges cross (not a simple polygon)");
  const Footprint cw = Normalized({{{1, -1}, {-1, -1}, {-1, 1}, {1, 1}}});
  EXPECT_EQ(cw.vertices.front(), Eigen::Vector2d(1, 1));
  EXPECT_THROW(ParseFootprintJson("{\"footprint\": [[1, 1], [2]]}", "f.json"), InputError);
  EXPECT_EQ(ParseFootprintJson("{\"footprint\": [[1, 1], [-1, 1], [-1, -1], [1, -1]]}", "f.json").vertices.size(), 4u);
}

// Issue 16 (fuzz targets path_planner, task_planner): a map message with a wall 1e39 m away
// made the field's grid counts overflow int; such a map is a setup error, every Plan refused.
TEST(Se2PlannerTest, AMapOfAbsurdExtentIsRefused) {
  std::vector<Segment> map = planner_test::Crossing(6.0, 20.0);
  const Se2Planner fine(map, Footprint::Rectangle(3.3, 10.0), Se2PlannerOptions{});
  EXPECT_EQ(fine.setup_error(), "");
  map.push_back({1.48707e39, 0.0, 1.48707e39, 1.0});
  const Se2Planner absurd(map, Footprint::Rectangle(3.3, 10.0), Se2PlannerOptions{});
  EXPECT_NE(absurd.setup_error().find("the map spans"), std::string::npos) << absurd.setup_error();
  EXPECT_EQ(absurd.Plan(Pose2(0, 0, 0), Pose2(0, 5, 0)).status, SearchStatus::kInvalidRequest);
}

// The clearance field against a test of every cell and every wall (what it computed before
// it visited only each wall's band): equal bit for bit, with long diagonal walls.
TEST(ClearanceFieldTest, EqualsTheDistanceOfEveryCellToEveryWall) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-30.0, 30.0);
  std::vector<Segment> walls;
  for (int i = 0; i < 25; ++i) walls.emplace_back(u(rng), u(rng), u(rng), u(rng));
  walls.emplace_back(-30.0, -30.0, 30.0, 29.0);
  walls.emplace_back(-30.0, 5.0, 30.0, 5.0);   // horizontal
  walls.emplace_back(7.0, -30.0, 7.0, 30.0);   // vertical
  walls.emplace_back(1.0, 1.0, 1.0, 1.0);      // a point
  const GridFrame frame = GridFrame::Covering(Eigen::Vector2d(-30, -30), Eigen::Vector2d(30, 30), 0.2, 0.0);
  const double cap = 4.3;
  const ClearanceField field(walls, frame, cap);
  for (int iy = 0; iy < frame.ny; ++iy)
    for (int ix = 0; ix < frame.nx; ++ix) {
      const Eigen::Vector2d centre = frame.CellMin(ix, iy).array() + 0.5 * frame.cell;
      double expected = cap;
      for (const Segment& w : walls) expected = std::min(expected, PointToSegmentDistance(centre, w));
      ASSERT_EQ(field.AtCell(ix, iy), expected) << "cell " << ix << ", " << iy;
    }
}

TEST(ClearanceFieldTest, ItsBoundsHoldTheTrueClearanceAnywhereOnEdgesAndCornersToo) {
  // The collision checker's quick decisions rest on these bounds: at random points, at
  // points on cell edges and corners (where the cell the bound reads may round either way)
  // and outside the frame, LowerBound <= the distance to the nearest wall <= UpperBound.
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-30.0, 30.0), wide(-33.0, 33.0);
  std::vector<Segment> walls;
  for (int i = 0; i < 20; ++i) walls.emplace_back(u(rng), u(rng), u(rng), u(rng));
  const GridFrame frame = GridFrame::Covering(Eigen::Vector2d(-30, -30), Eigen::Vector2d(30, 30), 0.2, 0.0);
  const double cap = 3.0;
  const ClearanceField field(walls, frame, cap);
  std::uniform_int_distribution<int> cell_x(0, frame.nx), cell_y(0, frame.ny);
  int bounded_above = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    Eigen::Vector2d p(wide(rng), wide(rng));
    if (trial % 3 == 1) p.x() = frame.x0 + cell_x(rng) * frame.cell;  // on a column edge
    if (trial % 3 == 2) p = frame.CellMin(cell_x(rng), cell_y(rng));  // on a corner
    double truth = std::numeric_limits<double>::infinity();
    for (const Segment& w : walls) truth = std::min(truth, PointToSegmentDistance(p, w));
    ASSERT_LE(field.LowerBound(p), truth + 1e-12) << p.transpose();
    const double upper = field.UpperBound(p);
    ASSERT_GE(upper, truth - 1e-12) << p.transpose();
    if (upper < cap) ++bounded_above;
  }
  EXPECT_GT(bounded_above, 5000);  // the upper bound is not only ever infinite
}

// Found by the fuzz targets (issue 16, path_planner): a map of long walls far apart. Each wall
// lowered every cell of its bounding box: a diagonal across a 1 km map is 2.5e7 cells at
// 0.2 m (minutes in the fuzz build). A wall now costs its band: (length / cell + 1) rows or
// columns of at most 2 (max_distance + cell) / cell + 3 cells each.
TEST(ClearanceFieldTest, ALongDiagonalWallCostsItsBandNotItsBox) {
  const GridFrame frame = GridFrame::Covering(Eigen::Vector2d(0, 0), Eigen::Vector2d(1000, 1000), 0.2, 0.0);
  const double cap = 6.0;
  const std::vector<Segment> walls = {{0.0, 0.0, 1000.0, 1000.0}, {0.0, 1000.0, 1000.0, 0.0}, {0.0, 500.0, 1000.0, 510.0}};
  const ClearanceField field(walls, frame, cap);
  double band = 0.0;  // the bound for the three walls, row by row (|dy| / cell + band rows)
  for (const Segment& w : walls) {
    const double rows = std::abs(w.b.y() - w.a.y()) / frame.cell + 2.0 * (cap + frame.cell) / frame.cell + 3.0;
    const double slope = std::abs(w.b.y() - w.a.y()) > 0.0 ? std::abs((w.b.x() - w.a.x()) / (w.b.y() - w.a.y())) : 1e9;
    const double per_row = std::min(std::abs(w.b.x() - w.a.x()), 2.0 * (cap + frame.cell) * slope) / frame.cell +
                           2.0 * (cap + frame.cell) / frame.cell + 3.0;
    band += rows * per_row;
  }
  EXPECT_LE(static_cast<double>(field.distance_tests()), band);
  EXPECT_LT(band, 0.1 * static_cast<double>(frame.size()));  // one diagonal's box alone was the frame
  // And the band is all the wall changes: cells near it are lowered, one beyond it is not.
  EXPECT_NEAR(field.At(Eigen::Vector2d(700.0, 700.0)), 0.0, 0.2);
  EXPECT_NEAR(field.At(Eigen::Vector2d(700.0, 703.0)), 3.0 / std::sqrt(2.0), 0.2);
  EXPECT_EQ(field.At(Eigen::Vector2d(700.0, 720.0)), cap);
}

TEST(FootprintCollisionTest, FieldAndExactTestAgreeWithBruteForce) {
  std::vector<Segment> map = planner_test::Crossing(6.0, 20.0);
  map.push_back({2.0, 8.0, 2.5, 9.0});  // a stone in the north arm
  Se2PlannerOptions o;
  o.clearance = 0.2;
  const Se2Planner planner(map, Footprint::Rectangle(3.3, 10.0), o);
  ASSERT_EQ(planner.setup_error(), "");
  testing::PathCheckSettings st = CheckerFor(planner);
  st.clearance = o.clearance + 0.5 * o.collision_step;  // the planner's internal margin
  // The map ends at the box of its segments: its sides are walls too.
  std::vector<Segment> walls = map;
  planner_test::AddBox(walls, -20, -20, 20, 20);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-20, 20), a(-kPi, kPi);
  int free = 0, blocked = 0;
  for (int i = 0; i < 3000; ++i) {
    const Pose2 p(u(rng), u(rng), a(rng));
    const bool brute_free = BruteForceFree(walls, p, st, 20.0);
    EXPECT_EQ(planner.PoseFree(p), brute_free) << p;
    (brute_free ? free : blocked)++;
  }
  EXPECT_GT(free, 50);
  EXPECT_GT(blocked, 1000);
}

TEST(FootprintCollisionTest, TheSpareOfEveryCheckHoldsAgainstBruteForce) {
  // A check that says free with s m to spare: every pose whose points all move at most s
  // (a translation t and a turn d about the origin with |t| + circumscribed |d| <= s) is free
  // by brute force with the margin. Poses near the walls (the exact test's spare) and in the
  // open (the discs').
  std::vector<Segment> crossing = planner_test::Crossing(6.0, 20.0);
  crossing.push_back({2.0, 8.0, 2.5, 9.0});
  const planner_test::CheckerWorld world(crossing);
  const std::vector<Segment>& walls = world.walls;
  const double margin = 0.075;
  const Footprint miner = Footprint::Rectangle(3.3, 10.0);
  const FootprintCollisionChecker checker(world.index, world.field, miner, margin);
  testing::PathCheckSettings st;
  st.polygon = miner.vertices;
  st.clearance = margin;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> along(-12, 12), across(-1.5, 1.5), a(-0.1, 0.1), unit(0, 1), dir(-kPi, kPi);
  int exact_spares = 0, moved = 0;
  for (int i = 0; i < 3000; ++i) {
    // In one of the four arms, roughly along it.
    const int arm = i % 4;
    Pose2 p = arm < 2 ? Pose2(along(rng), across(rng), a(rng) + arm * kPi) : Pose2(across(rng), along(rng), a(rng) + kPi / 2 + arm * kPi);
    const int64_t exact_before = checker.counters().exact_tests;
    const PoseCheck c = checker.Check(p);
    if (c.collides || c.spare <= 0.0) continue;
    exact_spares += checker.counters().exact_tests > exact_before;
    for (int k = 0; k < 5; ++k) {
      const double share = unit(rng), heading = dir(rng);
      const double t = share * c.spare, d = (1.0 - share) * c.spare / checker.circumscribed_radius();
      const Pose2 q(p.x + t * std::cos(heading), p.y + t * std::sin(heading), p.theta + (unit(rng) < 0.5 ? d : -d));
      ASSERT_TRUE(BruteForceFree(walls, q, st, 20.0)) << p << " spare " << c.spare << " moved to " << q;
      ++moved;
    }
  }
  EXPECT_GT(moved, 2000);
  EXPECT_GT(checker.counters().exact_tests, 300);
  EXPECT_GT(exact_spares, 100);
}

TEST(FootprintCollisionTest, DiscCoverHoldsThePolygonAndDecidesMostPosesInAnEntry) {
  const Footprint miner = Footprint::Rectangle(3.3, 10.0);
  const std::vector<Disc> discs = DiscCover(miner, 8);
  ASSERT_EQ(discs.size(), 8u);
  EXPECT_NEAR(discs.front().radius, std::hypot(0.625, 1.65), 1e-12);
  // Every point of the polygon is in some disc (a dense grid over the rectangle).
  for (double x = -5.0; x <= 5.0; x += 0.05)
    for (double y = -1.65; y <= 1.65; y += 0.05) {
      bool covered = false;
      for (const Disc& d : discs) covered = covered || (Eigen::Vector2d(x, y) - d.centre).norm() <= d.radius + 1e-12;
      ASSERT_TRUE(covered) << x << ", " << y;
    }
  // Along the middle of a 6 m corridor the discs decide nearly every pose without the exact test.
  const Se2Planner planner(planner_test::Corridor(60, 6), miner, {});
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> ux(8, 52), uy(-0.5, 0.5), a(-0.1, 0.1);
  int free = 0;
  for (int i = 0; i < 500; ++i) free += planner.PoseFree(Pose2(ux(rng), uy(rng), a(rng)));
  EXPECT_EQ(free, 500);
  const Se2PlanResult r = planner.Plan(Pose2(6, 0.5, 0.0), Pose2(54, -0.5, 0.0));
  ASSERT_EQ(r.status, SearchStatus::kFound) << r.reason;
  // (The exact tests are near the closed ends, 1 m behind the start and the goal.)
  EXPECT_GT(r.collisions.free_by_field, 2 * r.collisions.exact_tests)
      << r.collisions.free_by_field << " by the field, " << r.collisions.exact_tests << " exact";
}

TEST(FootprintCollisionTest, ARectanglesQuickExactTestAgreesWithTheGeneralPolygonTest) {
  // The miner as its 4 corners (the box path) and as the same rectangle with a fifth vertex
  // in the middle of its front edge (the general polygon path): the same answer and the same
  // spare at every pose near the walls of a crossing, with and without a margin.
  std::vector<Segment> walls = planner_test::Crossing(7.0, 20.0);
  walls.push_back({2.0, 8.0, 2.5, 9.0});
  const planner_test::CheckerWorld world(walls);
  const Footprint box = Footprint::Rectangle(3.3, 10.0);
  const Footprint five = planner_test::WithFrontMidpoint(box);
  ASSERT_EQ(five.vertices.size(), 5u);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-6, 6), a(-kPi, kPi);
  for (const double margin : {0.0, 0.125}) {
    const FootprintCollisionChecker quick(world.index, world.field, box, margin);
    const FootprintCollisionChecker general(world.index, world.field, five, margin);
    int collisions = 0, spares = 0;
    for (int i = 0; i < 4000; ++i) {
      const Pose2 p(u(rng), u(rng), a(rng));
      const double c = std::cos(p.theta), sn = std::sin(p.theta);
      const double q = quick.ExactSpare(p, c, sn), g = general.ExactSpare(p, c, sn);
      ASSERT_EQ(q < 0.0, g < 0.0) << p << " margin " << margin;
      if (g >= 0.0) {
        ASSERT_NEAR(q, g, 1e-9) << p;
      }
      collisions += g < 0.0;
      spares += g > 0.0 && g < FootprintCollisionChecker::kExactSpareCap;
    }
    EXPECT_GT(collisions, 1000) << "margin " << margin;
    EXPECT_GT(spares, 100) << "margin " << margin;
  }
}

TEST(FootprintCollisionTest, AnyPolygonAgreesWithBruteForce) {
  // A pentagon with a pointed nose (not a rectangle): the cover is of its bounding box, the
  // inside points are the disc centres inside it. Never free when brute force finds contact.
  std::vector<Segment> map = planner_test::Crossing(6.0, 20.0);
  map.push_back({-1.0, 9.0, -0.5, 9.5});
  const Footprint nose{{{4.5, 0.0}, {2.0, 1.4}, {-4.0, 1.4}, {-4.0, -1.4}, {2.0, -1.4}}};
  for (const double clearance : {0.0, 0.3}) {
    Se2PlannerOptions o;
    o.clearance = clearance;
    o.collision_discs = 5;
    const Se2Planner planner(map, nose, o);
    ASSERT_EQ(planner.setup_error(), "");
    testing::PathCheckSettings st = CheckerFor(planner);
    st.clearance = o.clearance + 0.5 * o.collision_step;
    std::vector<Segment> walls = map;
    planner_test::AddBox(walls, -20, -20, 20, 20);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-20, 20), a(-kPi, kPi);
    int free = 0, wrong = 0;
    for (int i = 0; i < 3000; ++i) {
      const Pose2 p(u(rng), u(rng), a(rng));
      const bool brute_free = BruteForceFree(walls, p, st, 20.0);
      wrong += planner.PoseFree(p) != brute_free;
      free += brute_free;
    }
    EXPECT_EQ(wrong, 0) << "clearance " << clearance;
    EXPECT_GT(free, 50);
  }
}

// Bellman-Ford over the grid mode's moves: the reference for the lazy Dijkstra.
std::vector<double> GridDistancesByRelaxation(const OccupancyGrid& grid, GridCell source) {
  std::vector<double> d(grid.blocked.size(), std::numeric_limits<double>::infinity());
  d[grid.Index(source.x, source.y)] = 0.0;
  for (bool changed = true; changed;) {
    changed = false;
    for (int y = 0; y < grid.height; ++y)
      for (int x = 0; x < grid.width; ++x)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            if ((dx == 0 && dy == 0) || !grid.Free(x, y) || !GridMoveAllowed(grid, x, y, dx, dy)) continue;
            const double via = d[grid.Index(x, y)] + (dx != 0 && dy != 0 ? std::sqrt(2.0) : 1.0);
            double& n = d[grid.Index(x + dx, y + dy)];
            if (via < n - 1e-12) n = via, changed = true;
          }
  }
  return d;
}

// Over several tiles (70 x 45 cells: tiles of 32, the last ones partial), asked in random order.
TEST(GridDijkstraTest, LazyDistancesEqualBellmanFord) {
  std::mt19937 rng(4);
  for (int trial = 0; trial < 6; ++trial) {
    const int w = 70, h = 45;
    OccupancyGrid grid(w, h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) grid.SetBlocked(x, y, rng() % 4 == 0);
    const GridCell source{static_cast<int>(rng() % w), static_cast<int>(rng() % h)};
    grid.SetBlocked(source.x, source.y, false);
    const std::vector<double> reference = GridDistancesByRelaxation(grid, source);
    LazyGridDistances lazy(grid, source);
    std::vector<size_t> order(reference.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    for (const size_t c : order) {
      const double d = lazy.Distance(static_cast<int>(c % w), static_cast<int>(c / w));
      if (std::isinf(reference[c]))
        ASSERT_TRUE(std::isinf(d)) << c;
      else
        ASSERT_NEAR(d, reference[c], 1e-9) << c;
    }
    EXPECT_EQ(GridDistancesFrom(grid, source).size(), reference.size());
  }
}

// A goal's distances cost what the search reaches, not the map: on a 600 m square of 0.2 m
// cells (9 million cells, 72 MB of distances as one array), a cell 10 cells away is answered
// from the few tiles around the source.
TEST(GridDijkstraTest, ADistanceNearTheSourceAllocatesOnlyTheTilesAroundIt) {
  OccupancyGrid grid(3000, 3000);
  LazyGridDistances lazy(grid, {1500, 1500});
  EXPECT_NEAR(lazy.Distance(1510, 1500), 10.0, 1e-12);
  EXPECT_NEAR(lazy.Distance(1493, 1493), 7.0 * std::sqrt(2.0), 1e-12);
  EXPECT_LE(lazy.cells_allocated(), 9u * 32 * 32);
}

TEST(GridDijkstraTest, HeadingCostsEqualBellmanFord) {
  const double kInf = std::numeric_limits<double>::infinity();
  // Brute force over the (cell, heading) graph's forward edges: a move ahead (1 or sqrt 2), a
  // move back at the reverse factor, a 45-degree turn at the cell's turn cost; Bellman-Ford
  // to the source state.
  std::mt19937 rng(9);
  for (int trial = 0; trial < 6; ++trial) {
    const int w = 12, h = 9;
    OccupancyGrid grid(w, h);
    std::vector<uint8_t> roomy(static_cast<size_t>(w * h));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        grid.SetBlocked(x, y, rng() % 5 == 0);
        roomy[grid.Index(x, y)] = rng() % 3 == 0;
      }
    const GridCell source{static_cast<int>(rng() % w), static_cast<int>(rng() % h)};
    grid.SetBlocked(source.x, source.y, false);
    const int source_heading = static_cast<int>(rng() % 8);
    const double turn = trial == 0 ? 0.0 : 2.5, reverse = trial == 0 ? 1.0 : 1.5, narrow = 4.0;
    LazyHeadingGridDistances lazy(grid, source, source_heading, turn, reverse, &roomy, narrow);
    std::vector<double> d(static_cast<size_t>(w * h * 8), kInf);
    d[grid.Index(source.x, source.y) * 8 + static_cast<size_t>(source_heading)] = 0.0;
    for (bool changed = true; changed;) {
      changed = false;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          if (!grid.Free(x, y)) continue;
          for (int k = 0; k < 8; ++k) {
            double& here = d[grid.Index(x, y) * 8 + static_cast<size_t>(k)];
            const double t = roomy[grid.Index(x, y)] ? turn : turn * narrow;
            double best = here;
            best = std::min(best, t + d[grid.Index(x, y) * 8 + static_cast<size_t>((k + 1) % 8)]);
            best = std::min(best, t + d[grid.Index(x, y) * 8 + static_cast<size_t>((k + 7) % 8)]);
            const double step = k % 2 == 1 ? std::sqrt(2.0) : 1.0;
            for (const int sign : {1, -1}) {
              const int dx = sign * LazyHeadingGridDistances::kDx[k], dy = sign * LazyHeadingGridDistances::kDy[k];
              if (!GridMoveAllowed(grid, x, y, dx, dy)) continue;
              best = std::min(best, step * (sign > 0 ? 1.0 : reverse) +
                                        d[grid.Index(x + dx, y + dy) * 8 + static_cast<size_t>(k)]);
            }
            if (best < here - 1e-12) here = best, changed = true;
          }
        }
    }
    const std::vector<double> plain = GridDistancesFrom(grid, source);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int k = 0; k < 8; ++k) {
          const double want = d[grid.Index(x, y) * 8 + static_cast<size_t>(k)];
          const double got = lazy.Distance(x, y, k);
          if (want == kInf) {
            ASSERT_EQ(got, kInf);
          } else {
            ASSERT_NEAR(got, want, 1e-9) << x << " " << y << " " << k;
            // Free turns and free reversing: the plain 2-D distance.
            if (trial == 0) {
              ASSERT_NEAR(got, plain[grid.Index(x, y)], 1e-9);
            }
          }
        }
  }
}

// A section of 2 x 2 pillars (12 m) with 6.5 m entries and crosscuts, its outer walls the
// boundary.
std::vector<Segment> SmallSection() {
  std::vector<Segment> m;
  const double room = 6.5, pillar = 12.0, side = 3 * room + 2 * pillar;
  planner_test::AddBox(m, 0, 0, side, side);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      const double x = room + i * (room + pillar), y = room + j * (room + pillar);
      planner_test::AddBox(m, x, y, x + pillar, y + pillar);
    }
  return m;
}

TEST(Se2PlannerTest, CornerToCornerThroughCorridorWaypointsWithinABoundOfExpansions) {
  // Corner to corner of a small section (two turns) with the heading-aware 2-D term and the
  // corridor waypoints: one waypoint in the middle of the crosscut, each leg a turn found by
  // the shot; the whole path accepted by the independent checker.
  const std::vector<Segment> map = SmallSection();
  Se2PlannerOptions o;
  o.clearance = 0.05;
  o.heuristic_turn_cost = 6.0;
  const Se2Planner planner(map, Footprint::Rectangle(3.3, 10.0), o);
  const Pose2 s(9.0, 3.25, 0.0), g(34.5, 40.25, 0.0);
  const std::vector<Pose2> waypoints = planner.Waypoints(s, g);
  ASSERT_EQ(waypoints.size(), 1u);
  EXPECT_NEAR(std::abs(NormalizeAngle(waypoints[0].theta - kPi / 2)), 0.0, 1e-9);
  EXPECT_TRUE(planner.PoseFree(waypoints[0]));
  SearchLimits limits;
  limits.max_expansions = 5000;
  const Se2PlanResult r = planner.Plan(s, g, limits);
  ASSERT_EQ(r.status, SearchStatus::kFound) << r.reason;
  const auto report = testing::CheckPath(map, s, AsChecked(r.path), CheckerFor(planner));
  EXPECT_TRUE(report.ok) << report.problem;
  EXPECT_GT(r.path.Length(), 25.5 + 37.0 - 10.0);
  EXPECT_LT(r.path.Length(), 80.0);
  // Facing back at the goal: the legs reverse or turn where there is room; still checked.
  const Se2PlanResult back = planner.Plan(s, Pose2(34.5, 40.25, kPi), SearchLimits{});
  ASSERT_EQ(back.status, SearchStatus::kFound) << back.reason;
  const auto back_report = testing::CheckPath(map, s, AsChecked(back.path), CheckerFor(planner));
  EXPECT_TRUE(back_report.ok) << back_report.problem;
  // A leg that fails (one expansion allowed: the first leg's shot does not reach the
  // waypoint) hands over to the whole search, whose path is checked too.
  Se2PlannerOptions tight = o;
  tight.corridor_leg_expansions = 1;
  const Se2Planner fallback(map, Footprint::Rectangle(3.3, 10.0), tight);
  const Se2PlanResult f = fallback.Plan(s, g, SearchLimits{});
  ASSERT_EQ(f.status, SearchStatus::kFound) << f.reason;
  EXPECT_GT(f.expansions, 1);
  const auto fallback_report = testing::CheckPath(map, s, AsChecked(f.path), CheckerFor(fallback));
  EXPECT_TRUE(fallback_report.ok) << fallback_report.problem;
}

TEST(Se2PlannerTest, RandomRequestsInARoomGiveCheckedPaths) {
  const std::vector<Segment> map = planner_test::Room(40, 30);
  Se2PlannerOptions o;
  o.clearance = 0.1;
  const Se2Planner planner(map, Footprint::Rectangle(3.3, 10.0), o);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> ux(6, 34), uy(6, 24), a(-kPi, kPi);
  int found = 0;
  for (int trial = 0; trial < 12; ++trial) {
    Pose2 s(ux(rng), uy(rng), a(rng)), g(ux(rng), uy(rng), a(rng));
    if (!planner.PoseFree(s) || !planner.PoseFree(g)) continue;
    const Se2PlanResult r = planner.Plan(s, g);
    ASSERT_EQ(r.status, SearchStatus::kFound) << r.reason;
    const auto report = testing::CheckPath(map, s, AsChecked(r.path), CheckerFor(planner));
    EXPECT_TRUE(report.ok) << report.problem;
    EXPECT_GE(report.min_clearance, o.clearance);
    EXPECT_NEAR(report.length, r.path.Length(), 1e-6);
    EXPECT_GE(r.path.Length() + 1e-9, TranslationDistance(s, g) - 1e-9);
    EXPECT_NEAR(TranslationDistance(r.path.pieces.back().end, g), 0.0, 1e-6);
    EXPECT_NEAR(HeadingDistance(r.path.pieces.back().end, g), 0.0, 1e-6);
    ++found;
  }
  EXPECT_GE(found, 6);
}

TEST(Se2PlannerTest, ARepeatedRequestGivesTheSamePathFromTheCachedHeuristic) {
  const std::vector<Segment> map = planner_test::Crossing(6.0, 20.0);
  const Se2Planner planner(map, Footprint::Rectangle(3.3, 10.0), {});
  const Pose2 s(0, -12, kPi / 2), g(12, 0, 0.0);
  const Se2PlanResult first = planner.Plan(s, g);
  ASSERT_EQ(first.status, SearchStatus::kFound) << first.reason;
  const Se2PlanResult other = planner.Plan(Pose2(0, -13, kPi / 2), Pose2(-12, 0, kPi));  // another goal between
  EXPECT_EQ(other.status, SearchStatus::kFound) << other.reason;
  const Se2PlanResult again = planner.Plan(s, g);
  ASSERT_EQ(again.status, SearchStatus::kFound) << again.reason;
  EXPECT_EQ(again.expansions, first.expansions);
  EXPECT_DOUBLE_EQ(again.cost, first.cost);
  ASSERT_EQ(again.path.pieces.size(), first.path.pieces.size());
  for (size_t i = 0; i < again.path.pieces.size(); ++i)
    EXPECT_EQ(again.path.pieces[i].end.translation(), first.path.pieces[i].end.translation());
  // Without the shot term the heuristic is admissible: the path is checked and no cheaper
  // than the first by more than the search's discretisation allows.
  Se2PlannerOptions admissible;
  admissible.shot_heuristic = false;
  const Se2Planner careful(map, Footprint::Rectangle(3.3, 10.0), admissible);
  const Se2PlanResult r = careful.Plan(s, g);
  ASSERT_EQ(r.status, SearchStatus::kFound) << r.reason;
  EXPECT_TRUE(testing::CheckPath(map, s, AsChecked(r.path), CheckerFor(careful)).ok);
  EXPECT_LE(r.cost, first.cost + 1e-9);
}

TEST(Se2PlannerTest, DrivesThroughACorridor) {
  const std::vector<Segment> map = planner_test::Corridor(60, 6);
  const Se2Planner planner(map, Footprint::Rectangle(3.3, 10.0), {});
  const Pose2 s(6, 0.5, 0.0), g(54, -0.5, 0.0);
  const Se2PlanResult r = planner.Plan(s, g);
  ASSERT_EQ(r.status, SearchStatus::kFound) << r.reason;
  const auto report = testing::CheckPath(map, s, AsChecked(r.path), CheckerFor(planner));
  EXPECT_TRUE(report.ok) << report.problem;
  EXPECT_LT(r.path.Length(), 49.0);  // barely longer than the 48 m between them
  EXPECT_EQ(r.path.Reversals(), 0);
  // Turning round is impossible in 6 m for a 10 m vehicle.
  const Se2PlanResult back = planner.Plan(s, Pose2(54, 0, kPi), [] {
    SearchLimits l;
    l.max_expansions = 3000;
    return l;
  }());
  EXPECT_NE(back.status, SearchStatus::kFound);
}

TEST(Se2PlannerTest, AFreeShotFromTheStartIsTheAnswerWithoutASearch) {
  // A 148 m straight run along a 6 m entry: the straight shot from the start is free, so it is
  // the answer (optimal: the straight line), found before the 2-D heuristic or any expansion.
  const std::vector<Segment> map = planner_test::Corridor(160, 6);
  const Se2Planner planner(map, Footprint::Rectangle(3.3, 10.0), {});
  const Pose2 s(6, 0.2, 0.0), g(154, 0.2, 0.0);
  const Se2PlanResult r = planner.Plan(s, g);
  ASSERT_EQ(r.status, SearchStatus::kFound) << r.reason;
  EXPECT_EQ(r.expansions, 1);
  EXPECT_NEAR(r.path.Length(), 148.0, 1e-6);
  EXPECT_NEAR(r.cost, 148.0, 1e-6);
  const auto report = testing::CheckPath(map, s, AsChecked(r.path), CheckerFor(planner));
  EXPECT_TRUE(report.ok) << report.problem;
  // Also with the heading-aware term and its corridor waypoints: the shot comes first.
  Se2PlannerOptions guided;
  guided.heuristic_turn_cost = 6.0;
  const Se2Planner guided_planner(map, Footprint::Rectangle(3.3, 10.0), guided);
  const Se2PlanResult rg = guided_planner.Plan(s, g);
  ASSERT_EQ(rg.status, SearchStatus::kFound) << rg.reason;
  EXPECT_EQ(rg.expansions, 1);
  EXPECT_NEAR(rg.path.Length(), 148.0, 1e-6);
  // The stop request is still heard before that shot.
  SearchLimits stopped;
  stopped.stop_requested = [] { return true; };
  EXPECT_EQ(planner.Plan(s, g, stopped).status, SearchStatus::kStopped);
  // A shot that is blocked (a 1.8 m stub from the entry's side wall in the middle) is not
  // taken: the search goes round it.
  std::vector<Segment> stub = planner_test::Corridor(60, 6);
  stub.push_back({30, -3, 30, -1.2});
  const Se2Planner around(stub, Footprint::Rectangle(3.3, 10.0), {});
  const Pose2 s2(6, 0, 0.0), g2(54, 0, 0.0);
  EXPECT_TRUE(around.PieceCollides(s2, {Motion::kForward, 48.0, 0.0, g2}));
  SearchLimits bounded;
  bounded.max_expansions = 50000;
  const Se2PlanResult a = around.Plan(s2, g2, bounded);
  ASSERT_EQ(a.status, SearchStatus::kFound) << a.reason;
  EXPECT_GT(a.expansions, 1);
  const auto report2 = testing::CheckPath(stub, s2, AsChecked(a.path), CheckerFor(around));
  EXPECT_TRUE(report2.ok) << report2.problem;
}

TEST(Se2PlannerTest, TurnsACornerWhereTurningInPlaceDoesNotFit) {
  // A 10 m x 3.3 m miner in the south entry of a crossing of two 6 m entries turns into the
  // east crosscut. Turning in place at the crossing does not fit (its circle is 10.5 m
  // across, the pillar corners are 4.24 m from the centre): arcs and short turns where the
  // polygon's sweep is free.
  const std::vector<Segment> map = planner_test::Crossing(6.0, 20.0);
  const Se2Planner planner(map, Footprint::Rectangle(3.3, 10.0), {});
  const Pose2 centre(0, 0, kPi / 2);
  EXPECT_TRUE(planner.PoseFree(centre));
  EXPECT_TRUE(planner.PieceCollides(centre, {Motion::kTurnInPlace, kPi / 4, 0.0, {}}));
  const Pose2 s(0, -12, kPi / 2), g(12, 0, 0.0);
  const Se2PlanResult r = planner.Plan(s, g);
  ASSERT_EQ(r.status, SearchStatus::kFound) << r.reason;
  const auto report = testing::CheckPath(map, s, AsChecked(r.path), CheckerFor(planner));
  EXPECT_TRUE(report.ok) << report.problem;
  EXPECT_GT(r.path.Length(), 16.0);  // at least the straight-line distance of 16.97 m, less rounding
  EXPECT_GT(r.path.Length(), 0.9 * std::hypot(12.0, 12.0));
}

// The largest clearance (m) of the miner at heading theta anywhere in a crossing of two
// `width` entries: the independent checker's distance at every centre of a 1 cm grid over
// the crossing (the walls' distance is 1-Lipschitz in the centre: the grid loses < 0.01 m).
double LargestClearanceInCrossing(double width, double theta) {
  const std::vector<Segment> map = planner_test::Crossing(width, 20.0);
  testing::PathCheckSettings st;
  st.polygon = Footprint::Rectangle(3.3, 10.0).vertices;
  double best = -1.0;
  for (double x = -3.0; x <= 3.0; x += 0.01)
    for (double y = -3.0; y <= 3.0; y += 0.01) {
      const auto report = testing::CheckPath(map, Pose2(x, y, theta), {}, st);
      if (report.ok) best = std::max(best, report.min_clearance);
    }
  return best;
}

TEST(Se2PlannerTest, AMinerTurningInA6mCrossingHasCentimetresAt45Degrees) {
  // Any turn from an entry into a crosscut passes heading 45 deg (mod 90); in a 6 m entry
  // the miner at 45 deg spans 10 sin 45 + 3.3 cos 45 = 9.4 m across, so that pose is in a
  // crossing. There, in the frame along (u) and across (v) the miner's axis through the
  // crossing's centre, the pillar corners are wedges with tips 3 sqrt 2 = 4.24 m out: the
  // miner's end corners (u = +-5, v = v0 - 1.65) clear the wedges of the pillars it points
  // at by (v0 - 2.41) / sqrt 2, its long side (v = v0 + 1.65) the third corner's tip by
  // 2.59 - v0: at best (v0 = 2.52) 0.077 m. The planner keeps clearance + collision_step / 2
  // (0.05 + 0.025 m in the bench): 2 mm of room before the walls' jitter (up to 0.2 m). In
  // 6.5 m entries the same construction gives 0.37 m.
  const double at_6 = LargestClearanceInCrossing(6.0, kPi / 4);
  EXPECT_GT(at_6, 0.06);
  EXPECT_LT(at_6, 0.08);
  const double at_65 = LargestClearanceInCrossing(6.5, kPi / 4);
  EXPECT_GT(at_65, 0.35);
  EXPECT_LT(at_65, 0.38);
}

TEST(Se2PlannerTest, TurnsAndBacksIntoA65mCrosscutWithTheBenchClearanceWithinABoundOfExpansions) {
  // With 6.5 m entries (0.37 m to spare at 45 deg, above) and the bench's 0.05 m clearance
  // the corner turns left and right are found in a few hundred expansions (61 measured), the
  // backing into the crosscut facing back (a cusp in the crossing) in under 40,000 (26,281).
  const std::vector<Segment> map = planner_test::Crossing(6.5, 20.0);
  Se2PlannerOptions o;
  o.clearance = 0.05;
  const Se2Planner planner(map, Footprint::Rectangle(3.3, 10.0), o);
  SearchLimits limits;
  const Pose2 s(0, -12, kPi / 2);
  for (const auto& [g, bound] : {std::pair{Pose2(12, 0, 0.0), 500}, std::pair{Pose2(-12, 0, kPi), 500},
                                 std::pair{Pose2(12, 0, kPi), 40000}}) {
    limits.max_expansions = bound;
    const Se2PlanResult r = planner.Plan(s, g, limits);
    ASSERT_EQ(r.status, SearchStatus::kFound) << r.reason;
    const auto report = testing::CheckPath(map, s, AsChecked(r.path), CheckerFor(planner));
    EXPECT_TRUE(report.ok) << report.problem;
    EXPECT_GT(r.path.Length(), 16.0);
  }
}

TEST(Se2PlannerTest, BacksIntoTheCrosscutWithAMultiPointManeuver) {
  // The same miner ends in the east crosscut facing back west, as before a slab cut: it
  // cannot turn round in 6 m, so the maneuver must reverse (forward into the crossing, back
  // into the crosscut). Coarser cells keep the test fast (the default finds it too).
  const std::vector<Segment> map = planner_test::Crossing(6.0, 20.0);
  Se2PlannerOptions o;
  o.heading_bins = 36;
  o.xy_resolution = 0.2;
  const Se2Planner planner(map, Footprint::Rectangle(3.3, 10.0), o);
  const Pose2 s(0, -12, kPi / 2), g(12, 0, kPi);
  const Se2PlanResult r = planner.Plan(s, g);
  ASSERT_EQ(r.status, SearchStatus::kFound) << r.reason;
  const auto report = testing::CheckPath(map, s, AsChecked(r.path), CheckerFor(planner));
  EXPECT_TRUE(report.ok) << report.problem;
  EXPECT_GE(r.path.Reversals(), 1);
  bool reverses = false;
  for (const MotionPiece& p : r.path.pieces) reverses = reverses || DriveDirection(p.motion) < 0;
  EXPECT_TRUE(reverses);
  EXPECT_GT(r.path.Length(), 16.0);
}

// A vehicle that stopped within the clearance of a wall leaves with what it has: the clearance
// less the sampling half-step (in 5 mm steps), or within that half-step clearance 0 and a
// finer collision step; every path from there keeps the clearance it was planned with (the
// independent checker samples every 2 mm). Contact, or within a millimetre of it, is refused.
TEST(Se2PlannerTest, AVehicleWithinTheClearanceOfAWallLeavesWithWhatItHas) {
  // A room with a pillar; the miner stopped below the pillar's south face (y = 6), heading east.
  std::vector<Segment> room = planner_test::Room(40, 24);
  planner_test::AddBox(room, 8, 6, 20, 12);
  Se2PlannerOptions o;
  o.clearance = 0.1;
  const Se2Planner planner(room, Footprint::Rectangle(3.3, 10.0), o);
  const Pose2 goal(33, 16, kPi / 2);
  const auto below_the_pillar = [](double gap) { return Pose2(14, 6.0 - 1.65 - gap, 0); };
  struct Case {
    double gap, clearance, step;  // m from the pillar; the options expected
  };
  for (const Case& c : {Case{0.5, 0.1, 0.05}, Case{0.083, 0.05, 0.05}, Case{0.032, 0.0, 0.05},
                        Case{0.0202, 0.0, 0.038}, Case{0.0042, 0.0, 0.006}}) {
    const Pose2 start = below_the_pillar(c.gap);
    const std::optional<Se2PlannerOptions> leaving = planner.LeavingOptions(start);
    ASSERT_TRUE(leaving.has_value()) << c.gap;
    EXPECT_NEAR(leaving->clearance, c.clearance, 1e-9) << c.gap;
    EXPECT_NEAR(leaving->collision_step, c.step, 1e-9) << c.gap;
    const Se2Planner leaves(room, planner.footprint(), *leaving);
    ASSERT_TRUE(leaves.PoseFree(start)) << c.gap;
    const Se2PlanResult r = leaves.Plan(start, goal);
    ASSERT_EQ(r.status, SearchStatus::kFound) << c.gap << ": " << r.reason;
    testing::PathCheckSettings st = CheckerFor(leaves);
    st.sample_step = 0.002;
    const auto report = testing::CheckPath(room, start, AsChecked(r.path), st);
    EXPECT_TRUE(report.ok) << c.gap << ": " << report.problem;
    EXPECT_GT(report.min_clearance, 0.0) << c.gap;
  }
  for (const double gap : {0.001, 0.0, -0.02})
    EXPECT_FALSE(planner.LeavingOptions(below_the_pillar(gap)).has_value()) << gap;
}

TEST(Se2PlannerTest, EveryBadRequestGetsAStatusAndAReason) {
  const std::vector<Segment> room = planner_test::Room(40, 30);
  const Footprint miner = Footprint::Rectangle(3.3, 10.0);
  const Se2Planner planner(room, miner, {});
  const Pose2 good(20, 15, 0), other(28, 15, 0);
  const auto expect = [](const Se2PlanResult& r, SearchStatus status, const std::string& words) {
    EXPECT_EQ(r.status, status) << r.reason;
    EXPECT_NE(r.reason.find(words), std::string::npos) << r.reason;
    EXPECT_TRUE(r.path.pieces.empty());
  };
  expect(planner.Plan({NAN, 1, 0}, good), SearchStatus::kInvalidRequest, "start (nan, 1, 0) is not finite");
  expect(planner.Plan(good, {1, 1, INFINITY}), SearchStatus::kInvalidRequest, "goal (1, 1, inf) is not finite");
  expect(planner.Plan({50, 15, 0}, good), SearchStatus::kInvalidRequest, "start (50, 15, 0) is outside the map");
  expect(planner.Plan({3, 15, 0}, good), SearchStatus::kInvalidRequest, "start (3, 15, 0) is in collision");
  expect(planner.Plan(good, {20, 1, 0}), SearchStatus::kInvalidRequest, "goal (20, 1, 0) is in collision");
  expect(Se2Planner({}, miner, {}).Plan(good, other), SearchStatus::kInvalidRequest, "the map has no segments");
  expect(Se2Planner(room, Footprint::Rectangle(50, 60), {}).Plan(good, other), SearchStatus::kInvalidRequest,
         "the footprint fits nowhere in the map");
  Se2PlannerOptions bad;
  bad.turn_radius = 0.0;
  expect(Se2Planner(room, miner, bad).Plan(good, other), SearchStatus::kInvalidRequest, "turn_radius must be > 0");
  expect(Se2Planner(room, Footprint{{{1, 1}, {2, 1}, {2, 2}}}, {}).Plan(good, other), SearchStatus::kInvalidRequest,
         "does not contain the vehicle's origin");
  // Two rooms with a wall between them: the 2-D heuristic knows before searching.
  std::vector<Segment> two = room;
  two.push_back({40, 0, 80, 0});
  two.push_back({80, 0, 80, 30});
  two.push_back({80, 30, 40, 30});
  const Se2Planner split(two, miner, {});
  expect(split.Plan(good, {60, 15, 0}), SearchStatus::kNoPath, "the goal is not reachable");
  // A gap the inscribed circle passes but the polygon cannot turn into: the search runs dry.
  std::vector<Segment> slot = planner_test::Room(40, 30);
  slot.push_back({40, 13, 70, 13});
  slot.push_back({40, 17, 70, 17});
  slot.push_back({70, 13, 70, 17});
  slot.erase(slot.begin() + 1);  // open the room's east wall
  slot.push_back({40, 0, 40, 13});
  slot.push_back({40, 17, 40, 30});
  const Se2Planner narrow(slot, miner, {});
  SearchLimits limits;
  limits.max_expansions = 300000;
  const Se2PlanResult dry = narrow.Plan(good, {60, 15, kPi / 2}, limits);
  EXPECT_NE(dry.status, SearchStatus::kFound);
  // Each bound stops the search and is named.
  const Se2Planner crossing(planner_test::Crossing(6.0, 20.0), miner, {});
  SearchLimits few;
  few.max_expansions = 5;
  expect(crossing.Plan({0, -12, kPi / 2}, {12, 0, 0}, few), SearchStatus::kExpansionLimit, "expansion_limit");
  SearchLimits small;
  small.max_states = 20;
  expect(crossing.Plan({0, -12, kPi / 2}, {12, 0, 0}, small), SearchStatus::kMemoryLimit, "memory_limit");
  SearchLimits deadline;
  deadline.stop_requested = [] { return true; };
  expect(crossing.Plan({0, -12, kPi / 2}, {12, 0, 0}, deadline), SearchStatus::kStopped, "stopped");
}

}  // namespace
}  // namespace minenav
