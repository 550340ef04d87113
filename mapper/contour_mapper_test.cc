#include "mapper/contour_mapper.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "evaluation/map_evaluation.h"
#include "mapper/test_world.h"

namespace minenav::mapper {
namespace {

using testing::MakeScan;
using testing::ScanSpec;
using testing::SmallRoomWorld;

LadarScan NoisyScan(const std::vector<Segment>& world, const Pose2& truth, unsigned seed) {
  ScanSpec spec;
  spec.num_points = 2048;
  spec.range_sigma = 0.03;
  spec.seed = seed;
  return MakeScan(world, truth, spec);
}

const std::vector<Pose2> kStations = {{3, 9, 0.3}, {9, 9.5, -0.5}, {17, 9, 2.0}, {17.5, 2, 1.0}, {9.5, 1.5, -2.5},
                                      {2.5, 2, 0.8}};

class ContourMapperTest : public ::testing::Test {
 protected:
  // Builds the small room from noisy scans with initial poses off by σ 0.33 m / 3.33°.
  void BuildRoom() { BuildRoomFor(mapper_); }

 public:
  static void BuildRoomFor(ContourMapper& mapper) {
    std::mt19937 rng(5);
    std::normal_distribution<double> xy(0, 0.33), th(0, DegToRad(3.33));
    for (size_t k = 0; k < kStations.size(); ++k) {
      const Pose2 initial = k == 0 ? kStations[0]
                                   : Pose2(kStations[k].x + xy(rng), kStations[k].y + xy(rng), kStations[k].theta + th(rng));
      const InsertResult r = mapper.InsertScan(NoisyScan(SmallRoomWorld(), kStations[k], static_cast<unsigned>(k + 1)), initial);
      ASSERT_TRUE(r.accepted) << "scan " << k << ": " << r.reason;
    }
  }

 protected:
  ContourMapper mapper_;
};

TEST_F(ContourMapperTest, OptionsAreValidated) {
  ContourMapperOptions o;
  EXPECT_EQ(ValidateOptions(o), "");
  o.pose.threshold_factor = 1.5;
  EXPECT_EQ(ValidateOptions(o).rfind("pose: ", 0), 0u);
}

TEST_F(ContourMapperTest, BuildsAnAccurateMapOfASmallRoom) {
  BuildRoom();
  const auto& scans = mapper_.scans();
  ASSERT_EQ(scans.size(), kStations.size());
  EXPECT_TRUE(scans[0].fixed);
  double worst = 0, worst_h = 0;
  for (size_t k = 0; k < scans.size(); ++k) {
    worst = std::max(worst, TranslationDistance(scans[k].pose, kStations[k]));
    worst_h = std::max(worst_h, HeadingDistance(scans[k].pose, kStations[k]));
  }
  EXPECT_LT(worst, 0.02);
  EXPECT_LT(RadToDeg(worst_h), 0.2);
  const MapDeviation dev = ContourDeviation(mapper_.map(), SmallRoomWorld());
  EXPECT_LT(dev.mean, 0.02);
  // Coverage of the true (noise-free) points of every station.
  std::vector<Eigen::Vector2d> truth_points;
  for (const Pose2& p : kStations) {
    const auto pts = ScanPointsInWorld(MakeScan(SmallRoomWorld(), p), p);
    truth_points.insert(truth_points.end(), pts.begin(), pts.end());
  }
  EXPECT_GT(Coverage(truth_points, mapper_.map(), 0.1), 0.95);
}

// NearestScans against a brute-force reference: the last scan, then the others by the
// distance of their sensor, ties going to the later one; returned in mapping order.
TEST(NearestScansTest, TheLastScanAndTheNearestInMappingOrder) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-20, 20);
  std::vector<MappedScan> scans(40);
  for (size_t k = 0; k < scans.size(); ++k) {
    scans[k].pose = Pose2(u(rng), u(rng), u(rng) / 10);
    scans[k].scan.sensor_position = Eigen::Vector2d(0.5, -0.2);
    scans[k].scan.utime = static_cast<int64_t>(k);  // identifies the scan
  }
  scans[7].pose = scans.back().pose;  // a tie at distance 0: both kept, the last first
  for (const int count : {1, 5, 12, 40, 100}) {
    const std::vector<MappedScan> got = NearestScans(scans, count);
    const Eigen::Vector2d here = scans.back().pose * scans.back().scan.sensor_position;
    std::vector<std::pair<double, int64_t>> all;
    for (const MappedScan& s : scans) all.emplace_back((s.pose * s.scan.sensor_position - here).norm(), s.scan.utime);
    std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first < b.first || (a.first == b.first && a.second > b.second); });
    std::vector<int64_t> expected;
    for (int k = 0; k < std::min<int>(count, 40); ++k) expected.push_back(all[static_cast<size_t>(k)].second);
    std::sort(expected.begin(), expected.end());
    std::vector<int64_t> ids;
    for (const MappedScan& s : got) ids.push_back(s.scan.utime);
    EXPECT_EQ(ids, expected) << "count " << count;
    EXPECT_EQ(ids.back(), 39) << "the new scan is always in";
  }
  EXPECT_TRUE(NearestScans({}, 5).empty());
}

// The live mapper's bounded insert (fit_scans, local_fit_radius: mapper/README.md "Insert
// cost") must map the small room to the same targets as the thesis's all-scan refit.
TEST(ContourMapperBoundedFitTest, NearestScansAndARadiusMapTheRoomAsAccurately) {
  ContourMapperOptions o;
  o.fit_scans = 3;
  o.local_fit_radius = 8.0;
  ContourMapper mapper(o);
  ASSERT_NO_FATAL_FAILURE(ContourMapperTest::BuildRoomFor(mapper));
  double worst = 0;
  for (size_t k = 0; k < mapper.scans().size(); ++k) worst = std::max(worst, TranslationDistance(mapper.scans()[k].pose, kStations[k]));
  EXPECT_LT(worst, 0.02);
  EXPECT_LT(ContourDeviation(mapper.map(), SmallRoomWorld()).mean, 0.02);
}

TEST_F(ContourMapperTest, RefusesScansThatWouldCorruptTheMap) {
  BuildRoom();
  const ContourMap before = mapper_.map();
  const size_t scans_before = mapper_.scans().size();
  auto unchanged = [&] {
    EXPECT_EQ(mapper_.scans().size(), scans_before);
    ASSERT_EQ(mapper_.map().NumContours(), before.NumContours());
    for (const auto& [id, c] : before.contours()) EXPECT_EQ(mapper_.map().Get(id).points, c.points);
  };
  // A scan that overlaps nothing (another room far away).
  InsertResult r = mapper_.InsertScan(NoisyScan(testing::Rectangle(100, 100, 104, 103), Pose2(102, 101, 0), 9),
                                      Pose2(102, 101, 0));
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.reason.find("overlap"), std::string::npos) << r.reason;
  unchanged();
  // Every reading out of range.
  LadarScan empty = NoisyScan(SmallRoomWorld(), kStations[1], 10);
  for (float& v : empty.ranges) v = std::nanf("");
  r = mapper_.InsertScan(empty, kStations[1]);
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.reason.find("too few usable points"), std::string::npos) << r.reason;
  unchanged();
  // A wildly wrong initial estimate: 9 m and 120 degrees off.
  r = mapper_.InsertScan(NoisyScan(SmallRoomWorld(), Pose2(10, 6, 0), 11), Pose2(1, 11, 2.1));
  EXPECT_FALSE(r.accepted) << r.reason;
  unchanged();
  // A malformed scan.
  LadarScan bad = NoisyScan(SmallRoomWorld(), kStations[1], 12);
  bad.max_range = -1;
  r = mapper_.InsertScan(bad, kStations[1]);
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.reason.find("invalid scan"), std::string::npos);
  unchanged();
  // And the mapper goes on: a good scan is still accepted.
  r = mapper_.InsertScan(NoisyScan(SmallRoomWorld(), Pose2(10, 6, 0), 13), Pose2(10.2, 5.8, 0.05));
  EXPECT_TRUE(r.accepted) << r.reason;
  EXPECT_LT(TranslationDistance(r.pose, Pose2(10, 6, 0)), 0.02);
}

TEST_F(ContourMapperTest, ScansWithHolesAreMappedAroundTheHoles) {
  LadarScan holey = NoisyScan(SmallRoomWorld(), kStations[0], 1);
  for (size_t i = 300; i < 700; ++i) holey.ranges[i] = std::nanf("");
  const InsertResult r = mapper_.InsertScan(holey, kStations[0]);
  ASSERT_TRUE(r.accepted) << r.reason;
  const InsertResult r2 = mapper_.InsertScan(NoisyScan(SmallRoomWorld(), kStations[1], 2), Pose2(9.2, 9.3, -0.45));
  ASSERT_TRUE(r2.accepted) << r2.reason;
  EXPECT_LT(TranslationDistance(r2.pose, kStations[1]), 0.02);
}

TEST_F(ContourMapperTest, FrontEndSeamAcceptsASmallInitialThreshold) {
  ASSERT_TRUE(mapper_.InsertScan(NoisyScan(SmallRoomWorld(), kStations[0], 1), kStations[0]).accepted);
  InsertOptions refined;
  refined.initial_threshold = 0.3;  // a front end already brought the pose within centimetres
  const Pose2 close(kStations[1].x + 0.05, kStations[1].y - 0.04, kStations[1].theta + 0.01);
  const InsertResult r = mapper_.InsertScan(NoisyScan(SmallRoomWorld(), kStations[1], 2), close, refined);
  ASSERT_TRUE(r.accepted) << r.reason;
  EXPECT_LT(r.estimation.iterations, 40);  // 0.3 m -> 0.1 m takes ~11 shrinking steps, not ~33
  EXPECT_LT(TranslationDistance(r.pose, kStations[1]), 0.02);
}

}  // namespace
}  // namespace minenav::mapper
