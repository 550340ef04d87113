// The segment index against brute force: ray casts identical to CastRay (common/geometry.h),
// radius queries a superset of the segments within the radius, the incremental index equal
// to a rebuild, the cells a segment touches equal to a test of every cell box, and no
// geometry (long, huge, non-finite) that makes it blow up.
#include "common/segment_index.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include "common/angle.h"
#include "common/file_io.h"
#include "tests/sanitizer.h"

namespace minenav {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A world with what trips ray casters up: a closed room and boxes with integer corners split
// into 1 m pieces (walls along cell boundaries, vertices shared by two segments), random
// polylines, long random segments, exact duplicates (ties: the lowest index wins) and a
// degenerate segment.
std::vector<Segment> RandomWorld(uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> corner(-3, 38), side(1, 6);
  std::uniform_real_distribution<double> in(-4.0, 44.0), step(0.2, 3.0), ang(-kPi, kPi), unit(0.0, 1.0);
  std::vector<Segment> w;
  auto box = [&](int x0, int y0, int x1, int y1) {
    for (int x = x0; x < x1; ++x) w.emplace_back(x, y0, x + 1, y0), w.emplace_back(x + 1, y1, x, y1);
    for (int y = y0; y < y1; ++y) w.emplace_back(x1, y, x1, y + 1), w.emplace_back(x0, y + 1, x0, y);
  };
  box(-5, -5, 45, 45);
  for (int k = 0; k < 6; ++k) {
    const int x = corner(rng), y = corner(rng);
    box(x, y, x + side(rng), y + side(rng));
  }
  for (int k = 0; k < 5; ++k) {
    Eigen::Vector2d p(in(rng), in(rng));
    for (int i = 0; i < 20; ++i) {
      const double t = ang(rng);
      const Eigen::Vector2d q = (p + step(rng) * Eigen::Vector2d(std::cos(t), std::sin(t))).cwiseMax(-4.0).cwiseMin(44.0);
      w.emplace_back(p, q);
      p = q;
    }
  }
  for (int k = 0; k < 10; ++k) w.emplace_back(in(rng), in(rng), in(rng), in(rng));
  const size_t n = w.size();
  for (int k = 0; k < 8; ++k) {
    const Segment& s = w[static_cast<size_t>(rng() % n)];
    w.push_back(unit(rng) < 0.5 ? s : Segment(s.b, s.a));
  }
  w.emplace_back(10.0, 10.0, 10.0, 10.0);
  return w;
}

// Compares the index and brute force on one ray; success when identical.
::testing::AssertionResult SameHit(const StaticSegmentIndex& grid, const Eigen::Vector2d& o, double bearing,
                                   double max_range) {
  const auto brute = CastRay(o, bearing, grid.segments(), max_range);
  const auto fast = grid.CastRay(o, bearing, max_range);
  if (brute.has_value() != fast.has_value())
    return ::testing::AssertionFailure() << "hit mismatch at (" << o.transpose() << ") bearing " << bearing
                                         << ": brute " << brute.has_value() << " grid " << fast.has_value();
  if (brute && (brute->range != fast->range || brute->segment != fast->segment))
    return ::testing::AssertionFailure() << "at (" << o.transpose() << ") bearing " << bearing << ": brute "
                                         << brute->range << " #" << brute->segment << ", grid " << fast->range
                                         << " #" << fast->segment;
  return ::testing::AssertionSuccess();
}

std::set<std::pair<int, int>> CellsByWalk(const GridFrame& f, const CellRange& window, const Segment& s) {
  std::set<std::pair<int, int>> out;
  ForEachCellTouched(f, window, s, kNoCellLimit, [&](int ix, int iy) {
    EXPECT_TRUE(out.emplace(ix, iy).second) << "cell listed twice";
  });
  return out;
}

// ---------------------------------------------------------------------------------------
// Cell geometry

TEST(SegmentIndexTest, CellCoordinatesNeverOverflow) {
  EXPECT_EQ(ClampedFloor(2.7, -5, 5), 2);
  EXPECT_EQ(ClampedFloor(-2.2, -5, 5), -3);
  EXPECT_EQ(ClampedFloor(1e300, -5, 5), 5);
  EXPECT_EQ(ClampedFloor(-1e300, -5, 5), -5);
  EXPECT_EQ(ClampedFloor(INFINITY, -5, 5), 5);
  EXPECT_EQ(ClampedFloor(std::nan(""), -5, 5), -5);
  // Every value near the integers and the bounds, against std::floor clamped.
  for (double v = -7.0; v <= 7.0; v += 0.03125)
    for (const double e : {-1e-12, 0.0, 1e-12}) {
      const double x = v + e;
      EXPECT_EQ(ClampedFloor(x, -5, 5), static_cast<int>(std::clamp(std::floor(x), -5.0, 5.0))) << x;
    }
  EXPECT_EQ(ClampedFloor(-0.0, -5, 5), 0);
  EXPECT_EQ(ClampedFloor(2147483647.5, 0, 2147483647), 2147483647);
  EXPECT_EQ(ClampedFloor(-2147483648.5, -2147483647 - 1, 0), -2147483647 - 1);
  GridFrame f;
  f.x0 = -1.0;
  f.cell = 0.5;
  f.nx = f.ny = 10;
  EXPECT_EQ(f.CellX(-0.75), 0);
  EXPECT_EQ(f.CellX(1e30), 10);
  EXPECT_EQ(f.CellX(-1e30), -1);
  EXPECT_EQ(f.CellY(std::nan("")), -1);
}

// Issue 16 (fuzz targets iconic_pose_estimator, path_planner, task_planner): a map message with
// a coordinate of 1e39 m made Covering's cell counts overflow int (undefined behaviour).
TEST(SegmentIndexTest, ACoveringOfAbsurdExtentIsABadInput) {
  const GridFrame mine = GridFrame::Covering({Segment(0, 0, 1000, 0), Segment(0, 500, 1000, 500)}, 0.25, 1.0);
  EXPECT_EQ(mine.nx, 4011);  // (1000 + 2 * (1 + 0.25)) / 0.25 + 1 cells
  EXPECT_EQ(mine.ny, 2011);
  EXPECT_THROW(GridFrame::Covering({Segment(0, 0, 1.48707e39, 0), Segment(0, 1, 1, 1)}, 0.2, 0.0), InputError);
  // The limit is on the cells, both ways: 16384 x 16385 is one row too many.
  EXPECT_NO_THROW(GridFrame::Covering(Eigen::Vector2d(0, 0), Eigen::Vector2d(16381, 16381), 1.0, 0.0));
  EXPECT_THROW(GridFrame::Covering(Eigen::Vector2d(0, 0), Eigen::Vector2d(16381, 16382), 1.0, 0.0), InputError);
}

// The walk along a segment lists exactly the cells a test of every cell box lists, and those
// are the cells the segment meets (up to the margin).
TEST(SegmentIndexTest, CellsTouchedEqualATestOfEveryCellBox) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int segments = 0;
  for (double cell : {0.1, 0.37, 1.0, 2.5}) {
    GridFrame f;
    f.x0 = -3.0 * cell + 0.123;
    f.y0 = -2.0 * cell - 0.71;
    f.cell = cell;
    f.nx = 30;
    f.ny = 24;
    const double w = f.nx * cell, h = f.ny * cell;
    auto point = [&](double over) {
      return Eigen::Vector2d(f.x0 - over * w + (1 + 2 * over) * w * unit(rng), f.y0 - over * h + (1 + 2 * over) * h * unit(rng));
    };
    auto lattice = [&] {
      return Eigen::Vector2d(f.x0 + cell * static_cast<int>(unit(rng) * f.nx), f.y0 + cell * static_cast<int>(unit(rng) * f.ny));
    };
    std::vector<Segment> tests;
    for (int k = 0; k < 150; ++k) {
      const Eigen::Vector2d a = point(0.1);
      tests.emplace_back(a, a + (0.3 + 3 * unit(rng)) * cell * Eigen::Vector2d(unit(rng) - 0.5, unit(rng) - 0.5));
      tests.emplace_back(point(0.3), point(0.3));                  // long, often leaving the grid
      const Eigen::Vector2d c = lattice(), e = lattice();
      tests.emplace_back(c, Eigen::Vector2d(e.x(), c.y()));       // along a row boundary
      tests.emplace_back(c, Eigen::Vector2d(c.x(), e.y()));       // along a column boundary
      tests.emplace_back(c, c + (1 + static_cast<int>(5 * unit(rng))) * cell * Eigen::Vector2d(1, 1));  // through corners
      tests.emplace_back(c, c);                                    // a point on a corner
    }
    for (const Segment& s : tests) {
      ++segments;
      const double margin = CellMargin(f, s);
      std::set<std::pair<int, int>> brute;
      for (int iy = 0; iy < f.ny; ++iy)
        for (int ix = 0; ix < f.nx; ++ix) {
          const bool touches = SegmentTouchesCell(f, ix, iy, s);
          if (touches) brute.emplace(ix, iy);
          const Eigen::Vector2d lo = f.CellMin(ix, iy), hi = lo + Eigen::Vector2d(cell, cell);
          const double d = BoxSegmentMinDistance(lo, hi, s);
          if (d == 0.0) {
            ASSERT_TRUE(touches) << "cell (" << ix << ", " << iy << ") met but not listed";
          }
          if (touches) {
            ASSERT_LE(d, 2 * margin) << "cell (" << ix << ", " << iy << ") listed but " << d << " away";
          }
        }
      ASSERT_EQ(CellsByWalk(f, f.Cells(), s), brute) << "cell " << cell << " segment " << s.a.transpose() << " -> "
                                                     << s.b.transpose();
      // A window of the grid: the same cells, restricted to it.
      const CellRange window{5, 3, 17, 20};
      std::set<std::pair<int, int>> inside;
      for (const auto& [ix, iy] : brute)
        if (ix >= window.x_lo && ix <= window.x_hi && iy >= window.y_lo && iy <= window.y_hi) inside.emplace(ix, iy);
      ASSERT_EQ(CellsByWalk(f, window, s), inside);
    }
  }
  EXPECT_GT(segments, 3000);
}

// A long segment costs cells along its line, not its bounding box: 10^5 columns in a frame
// of 10^6 x 10^6 cells, at most three cells per column; the cap stops the walk.
TEST(SegmentIndexTest, ALongSegmentCostsItsLengthNotItsBox) {
  GridFrame f;
  f.cell = 1.0;
  f.nx = f.ny = 1'000'000;
  const Segment s(0.5, 0.5, 100'000.3, 73'000.9);
  const auto t0 = std::chrono::steady_clock::now();
  int64_t n = 0;
  EXPECT_TRUE(ForEachCellTouched(f, f.Cells(), s, kNoCellLimit, [&](int, int) { ++n; }));
  // The walk over its bounding box would take hours; under the sanitizers this file is -O0.
  EXPECT_LT(SecondsSince(t0), 0.5 * testing::kSlowdown);
  EXPECT_GE(n, 100'000);
  EXPECT_LE(n, 3 * 100'001);
  int64_t capped = 0;
  EXPECT_FALSE(ForEachCellTouched(f, f.Cells(), s, 4096, [&](int, int) { ++capped; }));
  EXPECT_EQ(capped, 4096);
}

TEST(SegmentIndexTest, NonFiniteSegmentsTouchNoCell) {
  GridFrame f;
  f.nx = f.ny = 10;
  int calls = 0;
  for (const Segment& s : {Segment(0, 0, std::nan(""), 1), Segment(INFINITY, 0, 1, 1), Segment(0, -INFINITY, 1, 1)})
    EXPECT_FALSE(ForEachCellTouched(f, f.Cells(), s, kNoCellLimit, [&](int, int) { ++calls; }));
  EXPECT_EQ(calls, 0);
}

TEST(SegmentIndexTest, BoxDistancesMatchSampling) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  const Eigen::Vector2d lo(0, 0), hi(1, 1);
  for (int k = 0; k < 200; ++k) {
    const Segment s(u(rng), u(rng), u(rng), u(rng));
    double sampled_min = 1e9, sampled_max = 0.0;
    for (int i = 0; i <= 40; ++i)
      for (int j = 0; j <= 40; ++j) {
        const double d = PointToSegmentDistance({i / 40.0, j / 40.0}, s);
        sampled_min = std::min(sampled_min, d);
        sampled_max = std::max(sampled_max, d);
      }
    const double dmin = BoxSegmentMinDistance(lo, hi, s);
    EXPECT_LE(dmin, sampled_min + 1e-12);
    EXPECT_GE(dmin, sampled_min - 0.04);
    EXPECT_NEAR(BoxSegmentMaxDistance(lo, hi, s), sampled_max, 1e-12);
  }
}

// ---------------------------------------------------------------------------------------
// StaticSegmentIndex: ray casting

TEST(StaticSegmentIndexTest, RandomWorldsMatchBruteForce) {
  int rays = 0, hits = 0;
  for (uint32_t seed : {1u, 2u, 3u}) {
    const std::vector<Segment> world = RandomWorld(seed);
    for (double cell : {0.0, 0.25, 1.0, 4.0}) {
      const StaticSegmentIndex grid(world, cell);
      std::mt19937_64 rng(seed * 100 + static_cast<uint64_t>(cell * 4));
      std::uniform_real_distribution<double> uo(-12.0, 52.0), ub(-kPi, kPi), ur(0.0, 60.0);
      for (int i = 0; i < 6000; ++i) {
        const Eigen::Vector2d origin(uo(rng), uo(rng));
        const double range = i % 3 == 0 ? ur(rng) : 200.0;
        ASSERT_TRUE(SameHit(grid, origin, ub(rng), range)) << "seed " << seed << " cell " << cell;
        // Aimed exactly at a vertex (most are shared by two segments).
        const Segment& s = world[static_cast<size_t>(rng() % world.size())];
        const Eigen::Vector2d to = i % 2 ? s.a : s.b;
        if ((to - origin).norm() > 1e-9) {
          const double b = std::atan2(to.y() - origin.y(), to.x() - origin.x());
          ASSERT_TRUE(SameHit(grid, origin, b, range)) << "seed " << seed << " cell " << cell;
          hits += grid.CastRay(origin, b, 200.0).has_value();
        }
        rays += 2;
      }
      // Axis-aligned and diagonal rays from lattice points: along cell boundaries and walls.
      for (int x = -6; x <= 46; x += 2)
        for (int y = -6; y <= 46; y += 3)
          for (double b : {0.0, kPi / 2, kPi, -kPi / 2, kPi / 4, -3 * kPi / 4}) {
            ASSERT_TRUE(SameHit(grid, Eigen::Vector2d(x, y), b, 100.0)) << "seed " << seed << " cell " << cell;
            ++rays;
          }
    }
  }
  EXPECT_GT(rays, 170000);
  EXPECT_GT(hits, 50000);
}

TEST(StaticSegmentIndexTest, LongCrossingSegmentsMatchBruteForce) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-50.0, 50.0);
  std::vector<Segment> soup;
  for (int i = 0; i < 300; ++i) soup.emplace_back(u(rng), u(rng), u(rng), u(rng));
  soup.emplace_back(0, 0, 0, 0);  // degenerate
  for (double cell : {0.0, 0.25, 3.0}) {
    const StaticSegmentIndex grid(soup, cell);
    std::uniform_real_distribution<double> ub(-kPi, kPi);
    for (int i = 0; i < 5000; ++i) ASSERT_TRUE(SameHit(grid, Eigen::Vector2d(u(rng), u(rng)), ub(rng), 60.0));
  }
}

TEST(StaticSegmentIndexTest, EmptyWorldAndOutsideRays) {
  const StaticSegmentIndex empty({});
  EXPECT_FALSE(empty.CastRay(Eigen::Vector2d(0, 0), 0.0, 100.0).has_value());
  const StaticSegmentIndex one({Segment(10, -1, 10, 1)});
  const auto hit = one.CastRay(Eigen::Vector2d(0, 0), 0.0, 100.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_DOUBLE_EQ(hit->range, 10.0);
  EXPECT_EQ(hit->segment, 0);
  EXPECT_FALSE(one.CastRay(Eigen::Vector2d(0, 0), 0.0, 9.99).has_value());
  EXPECT_TRUE(one.CastRay(Eigen::Vector2d(0, 0), 0.0, 10.0).has_value());  // exactly at max range
  EXPECT_FALSE(one.CastRay(Eigen::Vector2d(0, 0), kPi, 100.0).has_value());
  EXPECT_FALSE(one.CastRay(Eigen::Vector2d(20, 0), 0.0, 100.0).has_value());
  // Non-finite input: no hit, no undefined behaviour.
  EXPECT_FALSE(one.CastRay(Eigen::Vector2d(NAN, 0), 0.0, 100.0).has_value());
  EXPECT_FALSE(one.CastRay(Eigen::Vector2d(0, 0), INFINITY, 100.0).has_value());
  EXPECT_FALSE(one.CastRay(Eigen::Vector2d(0, 0), 0.0, NAN).has_value());
  EXPECT_FALSE(one.CastRayDir(Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 0), 100.0).has_value());
}

// Non-finite and absurdly far segments are kept out of the cells (the grid stays the size of
// the sane part), yet every cast still gives the brute-force answer; a 20 km segment gets
// coarser cells, not gigabytes.
TEST(StaticSegmentIndexTest, HugeAndNonFiniteSegmentsStayBounded) {
  std::vector<Segment> world = RandomWorld(4);
  world.emplace_back(std::nan(""), 0.0, 5.0, 5.0);
  world.emplace_back(-INFINITY, 20.0, 50.0, 20.0);
  world.emplace_back(1e300, 1e300, -1e300, -1e300);
  world.emplace_back(-1e13, 21.5, 1e13, 21.5);  // beyond kMaxCoordinate: unlisted, still hit
  const auto t0 = std::chrono::steady_clock::now();
  const StaticSegmentIndex grid(world);
  EXPECT_LT(SecondsSince(t0), 0.1);
  EXPECT_EQ(grid.unlisted().size(), 4u);
  EXPECT_LT(grid.frame().size(), 10'000);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> uo(-12.0, 52.0), ub(-kPi, kPi);
  for (int i = 0; i < 5000; ++i) ASSERT_TRUE(SameHit(grid, Eigen::Vector2d(uo(rng), uo(rng)), ub(rng), 80.0));

  std::vector<Segment> far = RandomWorld(5);
  far.emplace_back(0.0, 0.0, 20'000.0, 20'000.0);
  const auto t1 = std::chrono::steady_clock::now();
  const StaticSegmentIndex coarse(far, 0.1);
  EXPECT_LT(SecondsSince(t1), 0.5);
  EXPECT_LE(static_cast<double>(coarse.frame().size()), StaticSegmentIndex::kMaxCells * 1.1);
  EXPECT_GT(coarse.cell_size(), 5.0);
  for (int i = 0; i < 2000; ++i) ASSERT_TRUE(SameHit(coarse, Eigen::Vector2d(uo(rng), uo(rng)), ub(rng), 80.0));
}

// Found by the fuzz targets (issue 16, ladar_driver and path_planner): a map of long walls far
// apart. One wall 8e10 m long beside short ones made a grid of 3 x 1.9e6 cells in which the
// wall alone touched 1.9e6 cells (40 s in the fuzz build). Whatever the walls, the (cell,
// segment) entries stay within the length budget plus 4 per segment, and the casts stay exact.
TEST(StaticSegmentIndexTest, LongWallsFarApartTouchABoundedNumberOfCells) {
  auto bound = [](size_t n) {
    const double dn = static_cast<double>(n);
    return std::max(StaticSegmentIndex::kMaxLengthCells, StaticSegmentIndex::kLengthCellsPerSegment * dn) + 4.0 * dn;
  };
  // The fuzz input's shape: short walls in x in [0, 20], one wall down to y = -8.2e10.
  std::vector<Segment> thin;
  for (int k = 0; k < 10; ++k) thin.emplace_back(2.0 * k, 0.0, 2.0 * k + 1.0, 0.5);
  thin.emplace_back(0.0, -8.24634e10, 20.0, 0.0);
  thin.emplace_back(20.0, -8.2e10, 0.0, -1.0);
  // Long walls far apart: 40 walls of 1e6 m, 1e4 m apart, both ways, and diagonals.
  std::vector<Segment> walls;
  for (int k = 0; k < 20; ++k) {
    walls.emplace_back(0.0, 1e4 * k, 1e6, 1e4 * k + 3.0);
    walls.emplace_back(1e4 * k, 0.0, 1e4 * k - 7.0, 1e6);
  }
  for (int k = 0; k < 10; ++k) walls.emplace_back(0.0, 1e4 * k, 1e6, 1e6 - 1e4 * k);
  for (const std::vector<Segment>* world : {&thin, &walls}) {
    for (const double cell : {0.0, 0.2}) {
      const StaticSegmentIndex grid(*world, cell);
      EXPECT_LE(static_cast<double>(grid.entries()), bound(world->size())) << "cell " << grid.cell_size();
      EXPECT_LE(static_cast<double>(grid.frame().size()), StaticSegmentIndex::kMaxCells * 1.1);
      std::mt19937_64 rng(5);
      std::uniform_real_distribution<double> ub(-kPi, kPi), ux(-10.0, 1e6), uy(-8e10, 1e6);
      for (int i = 0; i < 300; ++i) {
        const Eigen::Vector2d o(world == &thin ? 10.0 : ux(rng), world == &thin ? uy(rng) : ux(rng));
        ASSERT_TRUE(SameHit(grid, o, ub(rng), 1e7));
      }
    }
  }
  // The bound is no figure of today: the cell walk of the old sizing touched far more.
  const GridFrame old_thin{-0.5 * 42647.7, -8.24634e10 - 0.5 * 42647.7, 42647.7, 3, 1933599};
  int64_t old_cells = 0;
  ForEachCellTouched(old_thin, old_thin.Cells(), thin[10], kNoCellLimit, [&](int, int) { ++old_cells; });
  EXPECT_GT(static_cast<double>(old_cells), bound(thin.size()));
}

// A real map (segments of about the median length) keeps the cells of twice the median: the
// budget above never coarsens it.
TEST(StaticSegmentIndexTest, AnOrdinaryMapKeepsCellsOfTwiceTheMedianLength) {
  for (const uint32_t seed : {1u, 2u, 3u}) {
    const std::vector<Segment> world = RandomWorld(seed);
    std::vector<double> lengths;
    for (const Segment& s : world) lengths.push_back(s.length());
    std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2), lengths.end());
    EXPECT_EQ(StaticSegmentIndex(world).cell_size(), std::max(0.5, 2.0 * lengths[lengths.size() / 2]));
    EXPECT_EQ(StaticSegmentIndex(world, 0.3).cell_size(), 0.3);
  }
}

// ---------------------------------------------------------------------------------------
// Radius queries: a superset of brute force, exactly it after the distance filter

TEST(StaticSegmentIndexTest, RadiusQueriesContainEverySegmentWithinTheRadius) {
  const std::vector<Segment> world = RandomWorld(6);
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> uo(-8.0, 48.0), ur(0.0, 3.0);
  for (double cell : {0.0, 0.3, 2.0}) {
    const StaticSegmentIndex grid(world, cell);
    for (int q = 0; q < 1500; ++q) {
      const Eigen::Vector2d p(uo(rng), uo(rng));
      const double r = q % 10 == 0 ? 0.0 : ur(rng);
      std::set<int> truth;
      for (size_t i = 0; i < world.size(); ++i)
        if (PointToSegmentDistance(p, world[i]) <= r) truth.insert(static_cast<int>(i));
      const std::vector<int> got = grid.QueryPoint(p, r);
      ASSERT_TRUE(std::is_sorted(got.begin(), got.end()));
      std::set<int> filtered, visited;
      for (const int i : got)
        if (PointToSegmentDistance(p, world[static_cast<size_t>(i)]) <= r) filtered.insert(i);
      ASSERT_EQ(filtered, truth) << p.transpose() << " r " << r;
      grid.ForEachNear(p, r, [&](int i) {
        if (PointToSegmentDistance(p, world[static_cast<size_t>(i)]) <= r) visited.insert(i);
      });
      ASSERT_EQ(visited, truth);
    }
  }
}

TEST(StaticSegmentIndexTest, BoxQueriesContainEverySegmentWithinTheRadiusOfTheBox) {
  // ForEachNearBox: every segment within r of some point of [lo, hi] (brute force: the
  // box-to-segment distance), with boxes from a point to wider than a cell, long and thin.
  const std::vector<Segment> world = RandomWorld(10);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uo(-8.0, 48.0), us(0.0, 6.0), ur(0.0, 2.0);
  for (double cell : {0.0, 0.3, 2.0}) {
    const StaticSegmentIndex grid(world, cell);
    for (int q = 0; q < 1000; ++q) {
      const Eigen::Vector2d lo(uo(rng), uo(rng));
      const Eigen::Vector2d hi = lo + Eigen::Vector2d(us(rng), q % 3 == 0 ? 0.0 : us(rng));
      const double r = q % 10 == 0 ? 0.0 : ur(rng);
      std::set<int> truth, visited;
      for (size_t i = 0; i < world.size(); ++i)
        if (BoxSegmentMinDistance(lo, hi, world[i]) <= r) truth.insert(static_cast<int>(i));
      grid.ForEachNearBox(lo, hi, r, [&](int i) {
        if (BoxSegmentMinDistance(lo, hi, world[static_cast<size_t>(i)]) <= r) visited.insert(i);
      });
      ASSERT_EQ(visited, truth) << lo.transpose() << " .. " << hi.transpose() << " r " << r;
    }
  }
}

TEST(IncrementalSegmentIndexTest, RadiusQueriesContainEverySegmentWithinTheRadius) {
  std::mt19937 rng(9);
  const std::vector<Segment> world = RandomWorld(7);
  // The world in groups of 1 to 12 segments.
  IncrementalSegmentIndex grid(1.5);
  std::map<int, std::vector<Segment>> groups;
  for (size_t i = 0; i < world.size();) {
    const size_t n = std::min(world.size() - i, 1 + static_cast<size_t>(rng() % 12));
    const int id = static_cast<int>(groups.size()) * 3 - 20;  // negative ids too
    groups[id].assign(world.begin() + static_cast<std::ptrdiff_t>(i), world.begin() + static_cast<std::ptrdiff_t>(i + n));
    grid.Insert(id, groups[id]);
    i += n;
  }
  std::uniform_real_distribution<double> uo(-8.0, 48.0), ur(0.0, 3.0);
  for (int q = 0; q < 2000; ++q) {
    const Eigen::Vector2d p(uo(rng), uo(rng));
    const double r = q % 10 == 0 ? 0.0 : ur(rng);
    std::set<SegmentId> truth, filtered, visited;
    for (const auto& [id, segs] : groups)
      for (size_t k = 0; k < segs.size(); ++k)
        if (PointToSegmentDistance(p, segs[k]) <= r) truth.insert({id, static_cast<int>(k)});
    auto near = [&](const SegmentId& s) {
      return PointToSegmentDistance(p, groups.at(s.group)[static_cast<size_t>(s.index)]) <= r;
    };
    for (const SegmentId& s : grid.QueryPoint(p, r))
      if (near(s)) filtered.insert(s);
    ASSERT_EQ(filtered, truth) << p.transpose() << " r " << r;
    grid.ForEachNear(p, r, [&](const SegmentId& s) {
      if (near(s)) visited.insert(s);
    });
    ASSERT_EQ(visited, truth);
  }
}

// ---------------------------------------------------------------------------------------
// IncrementalSegmentIndex: edits

// Any sequence of inserts, re-inserts and removals leaves exactly the index a rebuild from
// the final groups gives (absurd segments included).
TEST(IncrementalSegmentIndexTest, InsertAndRemoveEqualARebuild) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> uo(-30.0, 30.0), step(0.1, 4.0), ang(-kPi, kPi), unit(0.0, 1.0);
  auto random_group = [&] {
    std::vector<Segment> g;
    Eigen::Vector2d p(uo(rng), uo(rng));
    const int n = 1 + static_cast<int>(rng() % 15);
    for (int i = 0; i < n; ++i) {
      const double t = ang(rng);
      const Eigen::Vector2d q = p + step(rng) * Eigen::Vector2d(std::cos(t), std::sin(t));
      g.emplace_back(p, q);
      p = q;
    }
    const double odd = unit(rng);
    if (odd < 0.05) g.emplace_back(0.0, 0.0, 30'000.0, -25'000.0);  // too many cells
    else if (odd < 0.08) g.emplace_back(std::nan(""), 0.0, 1.0, 1.0);
    else if (odd < 0.10) g.emplace_back(-500.0, 3.0, 600.0, 4.0);   // long, along its line
    return g;
  };
  IncrementalSegmentIndex grid(2.0);
  std::map<int, std::vector<Segment>> groups;
  for (int op = 0; op < 600; ++op) {
    const int id = static_cast<int>(rng() % 60);
    if (rng() % 4 == 0) {
      grid.Remove(id);
      groups.erase(id);
    } else {
      groups[id] = random_group();
      grid.Insert(id, groups[id]);
    }
  }
  IncrementalSegmentIndex rebuilt(2.0);
  for (const auto& [id, segs] : groups) rebuilt.Insert(id, segs);
  EXPECT_EQ(grid.NumEntries(), rebuilt.NumEntries());
  EXPECT_EQ(grid.NumUnindexed(), rebuilt.NumUnindexed());
  EXPECT_GT(grid.NumUnindexed(), 0u);
  for (int q = 0; q < 1000; ++q) {
    const Eigen::Vector2d p(uo(rng), uo(rng));
    const double r = 3.0 * unit(rng);
    ASSERT_EQ(grid.QueryPoint(p, r), rebuilt.QueryPoint(p, r));
    const Eigen::Vector2d lo = p - 20.0 * Eigen::Vector2d(unit(rng), unit(rng));
    ASSERT_EQ(grid.Query(lo, p, r), rebuilt.Query(lo, p, r));  // large boxes scan occupied cells
  }
  for (const auto& [id, segs] : groups) grid.Remove(id);
  EXPECT_EQ(grid.NumEntries(), 0u);
  EXPECT_TRUE(grid.QueryPoint({0, 0}, 100.0).empty());
}

// The absurd geometry of issue 11, item 7.

std::vector<Segment> Line(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return {Segment(a, b)}; }

bool Contains(const std::vector<SegmentId>& refs, const SegmentId& r) {
  return std::find(refs.begin(), refs.end(), r) != refs.end();
}

// Issue 11, item 7: one 20 km diagonal segment covers 10^8 cells of 2 m in its bounding box;
// listing it in each took 6 GB and 18-39 s until bad_alloc. Now it costs one entry.
TEST(IncrementalSegmentIndexTest, A20KilometreSegmentCostsOneEntryNotItsBoundingBox) {
  IncrementalSegmentIndex grid(2.0);
  const auto t0 = std::chrono::steady_clock::now();
  grid.Insert(7, Line({0, 0}, {20000, 20000}));
  EXPECT_LT(SecondsSince(t0), 0.1);
  EXPECT_EQ(grid.NumEntries(), 1u);
  EXPECT_EQ(grid.NumUnindexed(), 1u);
  // Still found where it is (every query returns it; callers test the exact distance).
  EXPECT_TRUE(Contains(grid.QueryPoint({10000, 10000.5}, 1.0), SegmentId{7, 0}));
  int visits = 0;
  grid.ForEachNear({15000, 15000}, 0.5, [&](const SegmentId& r) { visits += r == SegmentId{7, 0} ? 1 : 0; });
  EXPECT_EQ(visits, 1);
  grid.Remove(7);
  EXPECT_EQ(grid.NumEntries(), 0u);
  EXPECT_TRUE(grid.QueryPoint({10000, 10000}, 1.0).empty());
}

// A 1.5 km wall drawn as one diagonal segment: listed in the cells along it (at most three
// per 2 m column, some 1600), not the 280 000 of its box, and found from every point near it
// but not from afar.
TEST(IncrementalSegmentIndexTest, ALongSegmentIsListedAlongItsLine) {
  IncrementalSegmentIndex grid(2.0);
  grid.Insert(1, Line({-300, 100}, {760, 1160}));
  EXPECT_EQ(grid.NumUnindexed(), 0u);
  EXPECT_GT(grid.NumEntries(), 530u);   // at least one cell per 2 m column
  EXPECT_LT(grid.NumEntries(), 1700u);  // at most three per column
  for (double f = 0.0; f <= 1.0; f += 0.01) {
    const Eigen::Vector2d on = Eigen::Vector2d(-300, 100) + f * Eigen::Vector2d(1060, 1060);
    EXPECT_TRUE(Contains(grid.QueryPoint(on + Eigen::Vector2d(0.3, -0.3), 0.5), SegmentId{1, 0})) << f;
  }
  EXPECT_FALSE(Contains(grid.QueryPoint({500, 100}, 5.0), SegmentId{1, 0}));
}

// The walk along a segment must never miss a cell it passes through: for random long
// segments at every slope, every query point within `radius` of a segment gets it back.
TEST(IncrementalSegmentIndexTest, LineIndexingMissesNoSegmentNearAQueryPoint) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord(-400.0, 400.0), unit(0.0, 1.0), offset(-1.0, 1.0);
  IncrementalSegmentIndex grid(2.0);
  std::vector<Segment> segments;
  for (int id = 0; id < 60; ++id) {
    const Eigen::Vector2d a(coord(rng), coord(rng)), b(coord(rng), coord(rng));
    segments.emplace_back(a, b);
    grid.Insert(id, Line(a, b));
  }
  EXPECT_EQ(grid.NumUnindexed(), 0u);
  int checked = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const int id = static_cast<int>(rng() % segments.size());
    const Segment& s = segments[static_cast<size_t>(id)];
    const double radius = 0.05 + unit(rng);
    const Eigen::Vector2d near = s.a + unit(rng) * (s.b - s.a) + radius * Eigen::Vector2d(offset(rng), offset(rng)) / 1.5;
    if (PointToSegmentDistance(near, s) > radius) continue;
    ++checked;
    ASSERT_TRUE(Contains(grid.QueryPoint(near, radius), SegmentId{id, 0})) << trial;
    bool seen = false;
    grid.ForEachNear(near, radius, [&](const SegmentId& r) { seen = seen || r == SegmentId{id, 0}; });
    ASSERT_TRUE(seen) << trial;
  }
  EXPECT_GT(checked, 10000);
}

// Coordinates no map has (1e300, NaN) index without undefined behaviour and are returned.
TEST(IncrementalSegmentIndexTest, CoordinatesBeyondTheCellRangeAreKeptAsCandidates) {
  IncrementalSegmentIndex grid(2.0);
  grid.Insert(3, Line({1e300, 0}, {1e300, 1}));
  grid.Insert(4, Line({0, 0}, {std::nan(""), 1}));
  grid.Insert(5, Line({0, 0}, {1, 0}));
  EXPECT_EQ(grid.NumUnindexed(), 2u);
  const std::vector<SegmentId> near = grid.QueryPoint({0.5, 0}, 0.1);
  EXPECT_TRUE(Contains(near, SegmentId{3, 0}));
  EXPECT_TRUE(Contains(near, SegmentId{4, 0}));
  EXPECT_TRUE(Contains(near, SegmentId{5, 0}));
  EXPECT_FALSE(Contains(grid.QueryPoint({-1e12, 3e15}, 1.0), SegmentId{5, 0}));
}

// The segments the mapper makes (0.5 m, a few cells) are listed in every cell of their box,
// as before.
TEST(IncrementalSegmentIndexTest, ShortSegmentsAreListedInTheirBoundingBox) {
  IncrementalSegmentIndex grid(2.0);
  grid.Insert(2, Line({1.5, 1.5}, {2.5, 2.5}));  // box over cells (0..1, 0..1)
  EXPECT_EQ(grid.NumEntries(), 4u);
  EXPECT_TRUE(Contains(grid.QueryPoint({3.9, 0.1}, 0.0), SegmentId{2, 0}));  // cell (1, 0), off the line
}

}  // namespace
}  // namespace minenav
