// The offline survey against independent references: brute-force ray casting
// (common/geometry.h CastRay) for the ranges, the requested sigmas for the estimates.

#include "sim/survey.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <random>

#include "common/angle.h"
#include "sim/mine_generator.h"

namespace minenav {
namespace {

struct Stats {
  double n = 0, sum = 0, sum2 = 0;
  void Add(double v) {
    n += 1;
    sum += v;
    sum2 += v * v;
  }
  double mean() const { return sum / n; }
  double stddev() const { return std::sqrt(std::max(0.0, sum2 / n - mean() * mean())); }
};

MineOptions SmallMine() {
  MineOptions o;
  o.pillar_rows = 1;
  o.pillar_cols = 2;
  o.seed = 5;
  return o;
}

std::vector<SurveyRecord> Survey(const std::vector<std::vector<Segment>>& worlds, const std::vector<Station>& stations,
                                 const SurveyOptions& options) {
  std::vector<SurveyRecord> out;
  RunSurvey(worlds, stations, options, [&](const SurveyRecord& r) { out.push_back(r); });
  return out;
}

// Many stations spread over the free space of the small mine, for statistics.
std::vector<Station> ManyStations(int count, uint64_t seed) {
  const MineOptions mine = SmallMine();
  std::vector<Station> base = MineSurveyStations(mine, 12, 0.6);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.5, 0.5), heading(-kPi, kPi);
  std::vector<Station> out;
  for (int k = 0; k < count; ++k) {
    Station s = base[static_cast<size_t>(k) % base.size()];
    s.pose = Pose2(s.pose.x + jitter(rng), s.pose.y + jitter(rng), heading(rng));
    out.push_back(s);
  }
  return out;
}

TEST(Survey, OneScanPerStationKeyedByUtimeAtTheTruePose) {
  const std::vector<Segment> world = GenerateRoomAndPillarMine(SmallMine());
  const std::vector<Station> stations = MineSurveyStations(SmallMine(), 10, 0.6);
  SurveyOptions options;
  options.sensor.num_points = 512;
  options.sensor.angular_resolution = 0.0;
  options.start_utime = 5'000'000;
  options.station_interval = 1.0;
  const auto records = Survey({world}, stations, options);
  ASSERT_EQ(records.size(), stations.size());
  for (size_t k = 0; k < records.size(); ++k) {
    const SurveyRecord& r = records[k];
    EXPECT_EQ(r.index, static_cast<int>(k));
    EXPECT_EQ(r.utime, 5'000'000 + static_cast<int64_t>(k) * 1'000'000);
    EXPECT_EQ(r.scan.utime, r.utime);
    EXPECT_EQ(r.scan.scan_id, static_cast<int64_t>(k));
    EXPECT_EQ(r.scan.ranges.size(), 512u);
    EXPECT_EQ(r.truth.x, stations[k].pose.x);
    EXPECT_EQ(r.truth.theta, stations[k].pose.theta);
    // No estimate model: estimates are the truth.
    EXPECT_EQ(r.estimate.x, r.truth.x);
    EXPECT_EQ(r.estimate.y, r.truth.y);
  }
}

TEST(Survey, RangesMatchBruteForceRayCastingWithinTheRangeNoise) {
  const std::vector<Segment> world = GenerateRoomAndPillarMine(SmallMine());
  const std::vector<Station> stations = ManyStations(24, 3);
  SurveyOptions options;
  options.sensor.num_points = 720;
  options.sensor.angular_resolution = 0.0;
  options.sensor.mixed_pixel_probability = 0.0;  // outliers are tested by sensor_driver
  options.sensor.range_resolution = 0.0;
  options.seed = 11;
  const double sigma = options.sensor.range_sigma;
  Stats residual, perpendicular;
  int within_4_sigma = 0, valid = 0;
  for (const SurveyRecord& r : Survey({world}, stations, options)) {
    for (size_t i = 0; i < r.scan.ranges.size(); ++i) {
      if (!r.scan.IsValid(i)) continue;
      const double bearing = r.truth.theta + r.scan.Bearing(i);
      const auto hit = CastRay(r.truth.translation(), bearing, world, 1e3);
      ASSERT_TRUE(hit.has_value());
      // Readings near the far limit may be clipped by noise; skip them.
      if (hit->range > options.sensor.max_range - 5 * sigma || hit->range < options.sensor.min_range + 5 * sigma)
        continue;
      const double e = r.scan.ranges[i] - hit->range;
      residual.Add(e);
      ++valid;
      if (std::abs(e) < 4 * sigma) ++within_4_sigma;
      // Re-projected at the truth pose, the point lies on a wall within the noise.
      const Eigen::Vector2d p =
          r.truth.translation() + r.scan.ranges[i] * Eigen::Vector2d(std::cos(bearing), std::sin(bearing));
      double d = 1e9;
      for (const auto& s : world) d = std::min(d, PointToSegmentDistance(p, s));
      perpendicular.Add(d);
    }
  }
  ASSERT_GT(valid, 10000);
  // Beam divergence adds a little spread near grazing incidence; the bulk is Gaussian.
  EXPECT_NEAR(residual.mean(), 0.0, 0.005);
  EXPECT_NEAR(residual.stddev(), sigma, 0.15 * sigma);
  EXPECT_GT(static_cast<double>(within_4_sigma) / valid, 0.995);
  // Perpendicular distance to the wall is at most the range error.
  EXPECT_LT(perpendicular.mean(), sigma);
  EXPECT_GT(perpendicular.mean(), 0.2 * sigma);  // noise is really there
}

TEST(Survey, PoseNoiseHasTheRequestedSigmas) {
  const std::vector<Segment> world = GenerateRoomAndPillarMine(SmallMine());
  const std::vector<Station> stations = ManyStations(600, 4);
  SurveyOptions options;
  options.sensor.num_points = 8;  // the estimates are what is tested here
  options.sensor.angular_resolution = 0.0;
  options.estimate = InitialEstimateKind::kPoseNoise;
  options.pose_noise = {0.33, 0.2, DegToRad(3.33)};
  Stats dx, dy, dth;
  for (const SurveyRecord& r : Survey({world}, stations, options)) {
    dx.Add(r.estimate.x - r.truth.x);
    dy.Add(r.estimate.y - r.truth.y);
    dth.Add(NormalizeAngle(r.estimate.theta - r.truth.theta));
    EXPECT_NEAR(r.estimate_covariance(0, 0), 0.33 * 0.33, 1e-12);
  }
  // n = 600: the sample std is within ~3% (1 sigma) of the true one; allow 12%.
  EXPECT_NEAR(dx.stddev(), 0.33, 0.12 * 0.33);
  EXPECT_NEAR(dy.stddev(), 0.2, 0.12 * 0.2);
  EXPECT_NEAR(dth.stddev(), DegToRad(3.33), 0.12 * DegToRad(3.33));
  EXPECT_NEAR(dx.mean(), 0.0, 4 * 0.33 / std::sqrt(600.0));
  EXPECT_NEAR(dth.mean(), 0.0, 4 * DegToRad(3.33) / std::sqrt(600.0));
}

TEST(Survey, DriftAccumulatesAlongTheStationSequence) {
  const std::vector<Segment> world = GenerateRoomAndPillarMine(SmallMine());
  const std::vector<Station> stations = MineSurveyStations(SmallMine(), 20, 0.0);
  SurveyOptions options;
  options.sensor.num_points = 8;
  options.sensor.angular_resolution = 0.0;
  options.estimate = InitialEstimateKind::kDrift;
  options.drift.scale_error = 0.05;
  options.drift.heading_drift_per_metre = DegToRad(0.5);
  const auto records = Survey({world}, stations, options);
  // Noise-free drift: the first estimate is the truth, the error then grows.
  EXPECT_NEAR(TranslationDistance(records.front().estimate, records.front().truth), 0.0, 1e-12);
  const double mid = TranslationDistance(records[10].estimate, records[10].truth);
  const double last = TranslationDistance(records.back().estimate, records.back().truth);
  EXPECT_GT(mid, 0.5);
  EXPECT_GT(last, mid);
  // The path length so far times the scale error bounds the along-track error from below
  // only loosely; the heading drift must show: after ~80 m, ~40 deg * 0.5 deg/m.
  EXPECT_GT(HeadingDistance(records.back().estimate, records.back().truth), DegToRad(10));
}

TEST(Survey, DeterministicPerSeed) {
  const std::vector<Segment> world = GenerateRoomAndPillarMine(SmallMine());
  const std::vector<Station> stations = MineSurveyStations(SmallMine(), 6, 0.6);
  SurveyOptions options;
  options.sensor.num_points = 256;
  options.sensor.angular_resolution = 0.0;
  options.estimate = InitialEstimateKind::kPoseNoise;
  options.pose_noise = {0.1, 0.1, 0.05};
  options.seed = 9;
  const auto a = Survey({world}, stations, options);
  const auto b = Survey({world}, stations, options);
  options.seed = 10;
  const auto c = Survey({world}, stations, options);
  bool any_range_differs = false;
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].scan.ranges, b[k].scan.ranges);
    EXPECT_EQ(a[k].estimate.x, b[k].estimate.x);
    EXPECT_NE(a[k].estimate.x, c[k].estimate.x);
    any_range_differs = any_range_differs || a[k].scan.ranges != c[k].scan.ranges;
  }
  EXPECT_TRUE(any_range_differs);
}

TEST(Survey, EachStationSeesItsOwnWorld) {
  // World 1 adds a wall 3 m ahead of the station; world 0 has the room only.
  const std::vector<Segment> room = {Segment(-10, -10, 10, -10), Segment(10, -10, 10, 10), Segment(10, 10, -10, 10),
                                     Segment(-10, 10, -10, -10)};
  std::vector<Segment> with_wall = room;
  with_wall.emplace_back(3, -2, 3, 2);
  std::vector<Station> stations(2);
  stations[1].world = 1;
  SurveyOptions options;
  options.sensor = options.sensor.Ideal();
  options.sensor.num_points = 360;
  options.sensor.angular_resolution = 0.0;
  const auto r = Survey({room, with_wall}, stations, options);
  EXPECT_NEAR(r[0].scan.ranges[0], 10.0, 1e-5);  // bearing 0 is +x
  EXPECT_NEAR(r[1].scan.ranges[0], 3.0, 1e-5);

  stations[1].world = 2;
  try {
    Survey({room, with_wall}, stations, options);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("uses world 2 but only 2 world(s)"), std::string::npos) << e.what();
  }
}

// The small mine changed twice (thesis 4.8): world 1 closes the entry between the two
// pillars with a door at y = 10; world 2 has the door open again and a box (a vending
// machine) standing against the south boundary wall.
std::vector<std::vector<Segment>> ChangingSmallMine() {
  const std::vector<Segment> mine = GenerateRoomAndPillarMine(SmallMine());
  std::vector<Segment> door = mine;
  door.emplace_back(17.4, 10.0, 24.6, 10.0);  // ends buried in the pillars (walls within 0.6 m of 18 and 24)
  std::vector<Segment> box = mine;
  const std::vector<Eigen::Vector2d> corners = {{8.0, 0.8}, {10.6, 0.8}, {10.4, 1.7}, {8.2, 1.7}};
  for (size_t i = 0; i < corners.size(); ++i) box.emplace_back(corners[i], corners[(i + 1) % corners.size()]);
  return {mine, door, box};
}

TEST(Survey, ScansOfAChangingWorldMatchBruteForceRayCastingInTheirOwnWorld) {
  const auto worlds = ChangingSmallMine();
  std::vector<Station> stations = ManyStations(36, 6);
  const std::vector<int> sequence = {0, 0, 1, 1, 1, 2, 2, 0, 2};  // back and forth, runs and single steps
  for (size_t k = 0; k < stations.size(); ++k) stations[k].world = sequence[k % sequence.size()];
  SurveyOptions options;
  options.sensor.num_points = 720;
  options.sensor.angular_resolution = 0.0;
  options.sensor.mixed_pixel_probability = 0.0;
  options.sensor.range_resolution = 0.0;
  options.seed = 13;
  const double sigma = options.sensor.range_sigma;
  Stats residual;
  int valid = 0, within_4_sigma = 0;
  // Readings whose true range differs between the station's world and another world by
  // more than 10 sigma: where the change is visible. The scan must side with its own world.
  int changed = 0, changed_own = 0;
  const auto records = Survey(worlds, stations, options);
  ASSERT_EQ(records.size(), stations.size());
  for (size_t k = 0; k < records.size(); ++k) {
    const SurveyRecord& r = records[k];
    EXPECT_EQ(r.world, stations[k].world);
    EXPECT_EQ(r.world_changed, k == 0 || stations[k].world != stations[k - 1].world) << k;
    const auto& own = worlds[static_cast<size_t>(r.world)];
    for (size_t i = 0; i < r.scan.ranges.size(); ++i) {
      if (!r.scan.IsValid(i)) continue;
      const double bearing = r.truth.theta + r.scan.Bearing(i);
      const auto hit = CastRay(r.truth.translation(), bearing, own, 1e3);
      ASSERT_TRUE(hit.has_value());
      if (hit->range > options.sensor.max_range - 5 * sigma || hit->range < options.sensor.min_range + 5 * sigma)
        continue;
      const double e = r.scan.ranges[i] - hit->range;
      residual.Add(e);
      ++valid;
      if (std::abs(e) < 4 * sigma) ++within_4_sigma;
      for (size_t w = 0; w < worlds.size(); ++w) {
        if (static_cast<int>(w) == r.world) continue;
        const auto other = CastRay(r.truth.translation(), bearing, worlds[w], 1e3);
        ASSERT_TRUE(other.has_value());
        if (std::abs(other->range - hit->range) < 10 * sigma) continue;
        ++changed;
        if (std::abs(e) < std::abs(r.scan.ranges[i] - other->range)) ++changed_own;
      }
    }
  }
  ASSERT_GT(valid, 15000);
  EXPECT_NEAR(residual.mean(), 0.0, 0.005);
  EXPECT_NEAR(residual.stddev(), sigma, 0.15 * sigma);
  EXPECT_GT(static_cast<double>(within_4_sigma) / valid, 0.995);
  // The door and the box are seen from many stations; every such reading is nearer its own
  // world's wall than the other world's.
  EXPECT_GT(changed, 500);  // 1119 with this seed
  EXPECT_EQ(changed_own, changed);
}

TEST(Survey, RejectsBadOptionsInOneLine) {
  SurveyOptions options;
  options.station_interval = 0.0;
  EXPECT_NE(ValidateSurveyOptions(options), "");
  options = SurveyOptions{};
  options.estimate = InitialEstimateKind::kPoseNoise;
  options.pose_noise.sigma_x = -1;
  EXPECT_NE(ValidateSurveyOptions(options).find("sigma"), std::string::npos);
  options = SurveyOptions{};
  options.sensor.max_range = 0.5;
  EXPECT_NE(ValidateSurveyOptions(options).find("max_range"), std::string::npos);
}

}  // namespace
}  // namespace minenav
