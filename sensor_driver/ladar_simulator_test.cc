#include "sensor_driver/ladar_simulator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/angle.h"
#include "common/segment_index.h"
#include "sim/mine_generator.h"

namespace minenav {
namespace {

std::vector<Segment> Mine() {
  MineOptions o;
  return GenerateRoomAndPillarMine(o);
}

double NearestWall(const Eigen::Vector2d& p, const std::vector<Segment>& world) {
  double best = 1e300;
  for (const Segment& s : world) best = std::min(best, PointToSegmentDistance(p, s));
  return best;
}

TEST(LadarModelTest, PresetsAreValidAndMatchTheAppendices) {
  const LadarModel t = LadarModel::Typhoon();
  EXPECT_EQ(t.Validate(), "");
  EXPECT_EQ(t.num_points, 2048);
  EXPECT_DOUBLE_EQ(t.min_range, 1.5);
  EXPECT_DOUBLE_EQ(t.max_range, 45.0);
  EXPECT_DOUBLE_EQ(t.range_sigma, 0.044);
  EXPECT_DOUBLE_EQ(t.scan_rate, 10.0);
  EXPECT_NEAR(t.AngleStep() * 2048, 2 * kPi, 1e-12);
  for (int points : {512, 1024, 2048, 4096, 8192}) {
    const LadarModel c = LadarModel::Cyclone(points);
    EXPECT_EQ(c.Validate(), "") << points;
    EXPECT_DOUBLE_EQ(c.beam_divergence, 0.004);
    EXPECT_DOUBLE_EQ(c.range_resolution, 0.1);
    EXPECT_LE(c.scan_rate * points, 7200.0 + 1e-9);  // pulse rate limit
  }
  EXPECT_NE(LadarModel::Cyclone(0).Validate(), "");
}

TEST(LadarModelTest, ValidateNamesTheBadParameter) {
  auto bad = [](auto mutate, const std::string& name) {
    LadarModel m = LadarModel::Typhoon();
    mutate(m);
    const std::string why = m.Validate();
    EXPECT_NE(why.find(name), std::string::npos) << why;
    EXPECT_EQ(why.find('\n'), std::string::npos);
  };
  bad([](LadarModel& m) { m.num_points = 0; }, "num_points");
  bad([](LadarModel& m) { m.min_range = -1; }, "min_range");
  bad([](LadarModel& m) { m.max_range = 1.0; }, "max_range");
  bad([](LadarModel& m) { m.max_range = NAN; }, "max_range");
  bad([](LadarModel& m) { m.start_angle = INFINITY; }, "start_angle");
  bad([](LadarModel& m) { m.angular_resolution = 0.01; }, "angular_resolution");
  bad([](LadarModel& m) { m.range_resolution = -0.1; }, "range_resolution");
  bad([](LadarModel& m) { m.range_sigma = -0.1; }, "range_sigma");
  bad([](LadarModel& m) { m.beam_divergence = 1.0; }, "beam_divergence");
  bad([](LadarModel& m) { m.mixed_pixel_probability = 1.5; }, "mixed_pixel_probability");
  bad([](LadarModel& m) { m.mixed_pixel_min_gap = -1; }, "mixed_pixel_min_gap");
  bad([](LadarModel& m) { m.scan_rate = 0; }, "scan_rate");
  bad([](LadarModel& m) { m.sensor_id = ""; }, "sensor_id");
  EXPECT_THROW(LadarSimulator([] { LadarModel m; m.num_points = -3; return m; }(), 1), std::invalid_argument);
}

TEST(LadarSimulatorTest, NoiselessPointsLieOnTheWalls) {
  const std::vector<Segment> world = Mine();
  const StaticSegmentIndex grid(world);
  const LadarSimulator sim(LadarModel::Typhoon().Ideal(), 3);
  const Pose2 sensor_offset(0.4, -0.2, 0.1);
  int valid = 0;
  for (const Station& st : MineSurveyStations(MineOptions(), 42)) {
    const SimulatedScan s = sim.SimulateDetailed(grid, st.pose, sensor_offset, 1000, 5);
    const Pose2 world_T_sensor = st.pose * sensor_offset;
    for (size_t i = 0; i < s.scan.ranges.size(); ++i) {
      if (!s.scan.IsValid(i)) continue;
      ++valid;
      const double b = world_T_sensor.theta + s.scan.Bearing(i);
      const Eigen::Vector2d p = world_T_sensor.translation() + s.true_range[i] * Eigen::Vector2d(std::cos(b), std::sin(b));
      ASSERT_LT(PointToSegmentDistance(p, world[s.hit_segment[i]]), 1e-9);
      ASSERT_EQ(s.scan.ranges[i], static_cast<float>(s.true_range[i]));
    }
    // Through the public projection (float ranges): within float precision of a wall.
    for (const Eigen::Vector2d& p : ScanPointsInWorld(s.scan, st.pose)) ASSERT_LT(NearestWall(p, world), 2e-5);
  }
  EXPECT_GT(valid, 42 * 1900);  // the panel is closed: nearly every ray returns
}

TEST(LadarSimulatorTest, RangeLimitsAreRespected) {
  // Walls at 1 m (too near for Typhoon), 20 m, and none beyond 45 m in some directions.
  std::vector<Segment> world{Segment(1.0, -0.5, 1.0, 0.5), Segment(-20.0, -5.0, -20.0, 5.0),
                             Segment(-5.0, 20.0, 5.0, 20.0), Segment(-5.0, -60.0, 5.0, -60.0)};
  LadarModel m = LadarModel::Typhoon().Ideal();
  const SimulatedScan s = LadarSimulator(m, 1).SimulateDetailed(StaticSegmentIndex(world), Pose2(), Pose2(), 0, 0);
  int near = 0, far = 0, ok = 0;
  for (size_t i = 0; i < s.scan.ranges.size(); ++i) {
    const double t = s.true_range[i];
    if (s.hit_segment[i] == 0) {
      ++near;
      EXPECT_FALSE(s.scan.IsValid(i));
    } else if (s.hit_segment[i] == 3 || (s.hit_segment[i] < 0)) {
      EXPECT_FALSE(s.scan.IsValid(i)) << t;
      far += s.hit_segment[i] < 0;
    } else {
      ++ok;
      EXPECT_TRUE(s.scan.IsValid(i));
    }
  }
  EXPECT_GT(near, 100);
  EXPECT_GT(far, 1000);
  EXPECT_GT(ok, 100);
  // With noise, every valid reading is still inside [min, max].
  m = LadarModel::Typhoon();
  m.range_sigma = 0.5;
  world.emplace_back(-5.0, 44.8, 5.0, 44.8);  // near max range
  world.emplace_back(-0.3, -1.6, 0.3, -1.6);  // near min range
  for (int id = 0; id < 20; ++id) {
    const LadarScan scan = LadarSimulator(m, 9).Simulate(world, Pose2(), Pose2(), 0, id);
    for (size_t i = 0; i < scan.ranges.size(); ++i)
      if (scan.ranges[i] != 0.0f) {
        ASSERT_GE(scan.ranges[i], 1.5f);
        ASSERT_LE(scan.ranges[i], 45.0f);
      }
  }
}

TEST(LadarSimulatorTest, RangeResolutionQuantises) {
  LadarModel m = LadarModel::Cyclone(1024).Ideal();
  m.range_resolution = 0.1;
  m.min_range = 0.5;
  const std::vector<Segment> world = Mine();
  const Station st = MineSurveyStations(MineOptions(), 42)[10];
  const SimulatedScan s = LadarSimulator(m, 1).SimulateDetailed(StaticSegmentIndex(world), st.pose, Pose2(), 0, 0);
  int valid = 0;
  for (size_t i = 0; i < s.scan.ranges.size(); ++i) {
    if (!s.scan.IsValid(i)) continue;
    ++valid;
    const double q = s.scan.ranges[i] / 0.1;
    ASSERT_NEAR(q, std::round(q), 1e-4);
    ASSERT_LE(std::abs(s.scan.ranges[i] - s.true_range[i]), 0.05 + 1e-5);
  }
  EXPECT_GT(valid, 1000);
}

TEST(LadarSimulatorTest, NoiseStandardDeviationMatchesSigma) {
  LadarModel m = LadarModel::Typhoon().Ideal();
  m.range_sigma = 0.05;
  const std::vector<Segment> world = Mine();
  const StaticSegmentIndex grid(world);
  const LadarSimulator sim(m, 11);
  const Station st = MineSurveyStations(MineOptions(), 42)[20];
  double sum = 0.0, sum2 = 0.0;
  int n = 0;
  for (int id = 0; id < 10; ++id) {
    const SimulatedScan s = sim.SimulateDetailed(grid, st.pose, Pose2(), 0, id);
    for (size_t i = 0; i < s.scan.ranges.size(); ++i) {
      if (!s.scan.IsValid(i)) continue;
      const double e = s.scan.ranges[i] - s.true_range[i];
      sum += e;
      sum2 += e * e;
      ++n;
    }
  }
  ASSERT_GT(n, 15000);
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 4 * 0.05 / std::sqrt(n));
  EXPECT_NEAR(sd, 0.05, 0.005);  // within 10%
}

TEST(LadarSimulatorTest, FullTyphoonModelErrorIsNoisePlusQuantisation) {
  // Noise sigma and rounding to a step q add up to an rms range error of
  // sqrt(sigma^2 + q^2 / 12) away from mixed pixels; mixed pixels are few.
  const LadarModel m = LadarModel::Typhoon();
  const std::vector<Segment> world = Mine();
  const StaticSegmentIndex grid(world);
  const LadarSimulator sim(m, 21);
  double sum2 = 0.0;
  int n = 0, mixed = 0, valid = 0;
  for (const Station& st : MineSurveyStations(MineOptions(), 42)) {
    const SimulatedScan s = sim.SimulateDetailed(grid, st.pose, Pose2(), 0, 0);
    mixed += s.num_mixed;
    for (size_t i = 0; i < s.scan.ranges.size(); ++i) {
      if (!s.scan.IsValid(i)) continue;
      ++valid;
      if (s.mixed[i]) continue;
      const double e = s.scan.ranges[i] - s.true_range[i];
      sum2 += e * e;
      ++n;
    }
  }
  const double expected = std::sqrt(m.range_sigma * m.range_sigma + m.range_resolution * m.range_resolution / 12.0);
  EXPECT_NEAR(std::sqrt(sum2 / n), expected, 0.03 * expected);
  EXPECT_GT(mixed, 0);
  EXPECT_LT(mixed, valid / 50);  // a few per cent at most
}

TEST(LadarSimulatorTest, MixedPixelsOnlyAtOcclusionEdges) {
  LadarModel m = LadarModel::Cyclone(2048).Ideal();
  m.beam_divergence = 0.004;
  m.mixed_pixel_probability = 1.0;
  m.mixed_pixel_min_gap = 0.3;
  m.min_range = 0.5;
  const std::vector<Segment> world = Mine();
  const StaticSegmentIndex grid(world);
  const LadarSimulator sim(m, 5);
  int mixed = 0, edges = 0;
  for (const Station& st : MineSurveyStations(MineOptions(), 42)) {
    const SimulatedScan s = sim.SimulateDetailed(grid, st.pose, Pose2(), 0, 1);
    const size_t n = s.scan.ranges.size();
    for (size_t i = 0; i < n; ++i) {
      const double b = st.pose.theta + s.scan.Bearing(i);
      // Edges that see nothing within max_range do not mix (no far return to mix with).
      const auto l = CastRay(st.pose.translation(), b + 0.002, world, m.max_range);
      const auto r = CastRay(st.pose.translation(), b - 0.002, world, m.max_range);
      const bool edge = l && r && s.true_range[i] > 0 &&
                        std::max({l->range, r->range, s.true_range[i]}) -
                                std::min({l->range, r->range, s.true_range[i]}) > 0.3;
      edges += edge;
      ASSERT_EQ(s.mixed[i] != 0, edge) << "reading " << i;
      if (s.mixed[i]) {
        ++mixed;
        // Mixed ranges lie between the near and the far surface.
        const double near = std::min({l->range, r->range, s.true_range[i]});
        const double far = std::max({l->range, r->range, s.true_range[i]});
        if (s.scan.IsValid(i)) {
          ASSERT_GE(s.scan.ranges[i], near - 1e-5);
          ASSERT_LE(s.scan.ranges[i], far + 1e-5);
        }
      } else if (s.true_range[i] >= m.min_range && s.true_range[i] <= m.max_range) {
        ASSERT_EQ(s.scan.ranges[i], static_cast<float>(s.true_range[i]));
      }
    }
    EXPECT_EQ(s.num_mixed, static_cast<int>(std::count(s.mixed.begin(), s.mixed.end(), 1)));
  }
  EXPECT_GT(mixed, 42);  // pillars occlude each other from every station
  EXPECT_EQ(mixed, edges);
}

TEST(LadarSimulatorTest, DeterministicPerSeedAndScanId) {
  const std::vector<Segment> world = Mine();
  const StaticSegmentIndex grid(world);
  const Pose2 pose = MineSurveyStations(MineOptions(), 42)[3].pose;
  const LadarSimulator a(LadarModel::Cyclone(1024), 7), b(LadarModel::Cyclone(1024), 7), c(LadarModel::Cyclone(1024), 8);
  const LadarScan a2 = a.Simulate(grid, pose, Pose2(), 10, 2);
  const LadarScan a1 = a.Simulate(grid, pose, Pose2(), 10, 1);
  EXPECT_EQ(b.Simulate(grid, pose, Pose2(), 10, 1).ranges, a1.ranges);  // order does not matter
  EXPECT_EQ(b.Simulate(world, pose, Pose2(), 10, 2).ranges, a2.ranges);  // vector overload, same answer
  EXPECT_NE(a1.ranges, a2.ranges);
  EXPECT_NE(c.Simulate(grid, pose, Pose2(), 10, 1).ranges, a1.ranges);
  EXPECT_EQ(a1.utime, 10);
  EXPECT_EQ(a1.scan_id, 1);
  EXPECT_EQ(a1.sensor_id, "cyclone");
  EXPECT_EQ(ValidateScan(a1), "");
  EXPECT_NEAR(a1.scan_duration, 1023.0 / 1024.0 / 5.0, 1e-12);
}


// The ladar's ray casting (common/segment_index.h) on the synthetic mine must give exactly
// what brute force (common/geometry.h CastRay) gives (the index's own tests, on worlds built
// inline, are in common/segment_index_test.cc).
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

TEST(LadarRayCastingTest, RandomRaysInSyntheticMineMatchBruteForce) {
  MineOptions o;
  o.pillar_rows = 3;
  o.pillar_cols = 4;
  const std::vector<Segment> world = GenerateRoomAndPillarMine(o);
  const Eigen::Vector2d size = MinePanelSize(o);
  for (double cell : {0.0, 0.37, 1.0, 5.0}) {
    const StaticSegmentIndex grid(world, cell);
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> ux(-10.0, size.x() + 10.0), uy(-10.0, size.y() + 10.0);
    std::uniform_real_distribution<double> ub(-kPi, kPi), ur(0.0, 80.0);
    int hits = 0;
    for (int i = 0; i < 20000; ++i) {
      const Eigen::Vector2d origin(ux(rng), uy(rng));
      const double range = i % 3 == 0 ? ur(rng) : 200.0;
      ASSERT_TRUE(SameHit(grid, origin, ub(rng), range)) << "cell " << cell;
      hits += CastRay(origin, 0.3, world, 200.0).has_value();
    }
    EXPECT_GT(hits, 1000);
  }
}

TEST(LadarRayCastingTest, DegenerateRaysMatchBruteForce) {
  MineOptions o;
  const std::vector<Segment> world = GenerateRoomAndPillarMine(o);
  const StaticSegmentIndex grid(world, 1.0);
  // Rays from every 7th vertex towards other vertices (through shared endpoints), and
  // axis-aligned rays from points on cell boundaries.
  for (size_t i = 0; i < world.size(); i += 7) {
    for (size_t j = 3; j < world.size(); j += 29) {
      const Eigen::Vector2d from = world[i].a, to = world[j].b;
      if ((to - from).norm() < 1e-9) continue;
      const double bearing = std::atan2(to.y() - from.y(), to.x() - from.x());
      ASSERT_TRUE(SameHit(grid, from, bearing, 100.0));
      ASSERT_TRUE(SameHit(grid, from + Eigen::Vector2d(0.5, 0.5), bearing, 100.0));
    }
  }
  for (double x = -2.0; x < 70.0; x += 1.0)
    for (double y = -2.0; y < 50.0; y += 1.0)
      for (double b : {0.0, kPi / 2, kPi, -kPi / 2, kPi / 4, -3 * kPi / 4})
        ASSERT_TRUE(SameHit(grid, Eigen::Vector2d(x, y), b, 100.0));
}

}  // namespace
}  // namespace minenav
