// MeasureRangeNoise against scans ray-cast with known noise: the Typhoon's and the Cyclone's
// (full turn, 2048 readings, noise and quantisation), a SICK's (180 degrees at 1 degree, where
// the second difference of the ranges would read the walls' obliquity as noise), an exact scan,
// and too few readings.
#include "common/range_noise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "common/angle.h"
#include "common/geometry.h"
#include "common/pose2.h"

namespace minenav {
namespace {

// A 20 x 12 m room with a 2 x 1.5 m pillar and a slanted wall across one corner.
std::vector<Segment> Room() {
  return {{0, 0, 20, 0},   {20, 0, 20, 9},  {20, 9, 17, 12}, {17, 12, 0, 12}, {0, 12, 0, 0},
          {12, 5, 14, 5},  {14, 5, 14, 6.5}, {14, 6.5, 12, 6.5}, {12, 6.5, 12, 5}};
}

LadarScan Cast(const Pose2& sensor, int points, double field_of_view, double sigma, double quantum,
               unsigned seed) {
  LadarScan scan;
  scan.start_angle = -0.5 * field_of_view;
  scan.angle_step = field_of_view / (field_of_view >= 2.0 * kPi ? points : points - 1);
  scan.min_range = 0.5;
  scan.max_range = 45.0;
  scan.range_resolution = quantum;
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  const std::vector<Segment> world = Room();
  for (int i = 0; i < points; ++i) {
    const auto hit = CastRay(sensor.translation(), sensor.theta + scan.Bearing(static_cast<size_t>(i)), world, 45.0);
    double r = hit ? hit->range + sigma * noise(rng) : std::nan("");
    if (quantum > 0.0) r = quantum * std::round(r / quantum);
    scan.ranges.push_back(static_cast<float>(r));
  }
  return scan;
}

const Pose2 kStations[] = {Pose2(4.0, 3.0, 0.3), Pose2(9.5, 8.0, -2.0), Pose2(17.0, 3.5, 1.2)};

// Within `tolerance` (a fraction) of the noise the readings carry (sigma^2 + q^2 / 12), from
// every station.
void ExpectMeasured(int points, double field_of_view, double sigma, double quantum, double tolerance) {
  const double carried = std::sqrt(sigma * sigma + quantum * quantum / 12.0);
  unsigned seed = 1;
  for (const Pose2& station : kStations) {
    const RangeNoise m = MeasureRangeNoise(Cast(station, points, field_of_view, sigma, quantum, seed++));
    EXPECT_GT(m.triples, points * 8 / 10) << station.x;
    EXPECT_NEAR(m.sigma, carried, tolerance * carried) << "sigma " << sigma << " q " << quantum << " at " << station.x;
  }
}

TEST(RangeNoise, MeasuresTheTyphoonsNoise) { ExpectMeasured(2048, 2.0 * kPi, 0.044, 0.044, 0.1); }

TEST(RangeNoise, MeasuresTheCyclonesNoise) { ExpectMeasured(2048, 2.0 * kPi, 0.10, 0.10, 0.1); }

// 181 readings: the estimate's own spread is about 6 %, and the corners spoil more of them.
TEST(RangeNoise, MeasuresASicksNoiseAtOneDegree) { ExpectMeasured(181, kPi, 0.01, 0.01, 0.2); }

TEST(RangeNoise, MeasuresNoiseWithoutQuantisation) { ExpectMeasured(1000, 2.0 * kPi, 0.02, 0.0, 0.1); }

// The second difference of the ranges, which this replaced, reads an oblique wall at 1 degree
// as noise: from a station near a corner of the room, several times the true 2 mm.
TEST(RangeNoise, AnObliqueWallIsNotNoise) {
  const LadarScan scan = Cast(Pose2(1.0, 1.0, 0.8), 181, kPi, 0.002, 0.0, 7);
  std::vector<double> second;
  for (size_t i = 1; i + 1 < scan.ranges.size(); ++i)
    if (scan.IsValid(i - 1) && scan.IsValid(i) && scan.IsValid(i + 1))
      second.push_back(std::abs(scan.ranges[i - 1] - 2.0 * scan.ranges[i] + scan.ranges[i + 1]));
  std::nth_element(second.begin(), second.begin() + static_cast<std::ptrdiff_t>(second.size() / 2), second.end());
  const double by_second_difference = 1.4826 * second[second.size() / 2] / std::sqrt(6.0);
  EXPECT_GT(by_second_difference, 2.0 * 0.002);
  EXPECT_NEAR(MeasureRangeNoise(scan).sigma, 0.002, 0.2 * 0.002);
}

TEST(RangeNoise, AnExactScanHasNone) {
  const RangeNoise m = MeasureRangeNoise(Cast(kStations[0], 2048, 2.0 * kPi, 0.0, 0.0, 1));
  EXPECT_GT(m.triples, 1500);
  EXPECT_LT(m.sigma, 1e-4);  // float ranges: micrometres
}

// A scan whose bearings are not numbers (a hostile angle_step) measures nothing, and no NaN
// reaches the median.
TEST(RangeNoise, NoBearingsNoEstimate) {
  LadarScan scan = Cast(kStations[0], 2048, 2.0 * kPi, 0.044, 0.0, 1);
  scan.angle_step = std::nan("");
  const RangeNoise m = MeasureRangeNoise(scan);
  EXPECT_EQ(m.triples, 0);
  EXPECT_EQ(m.sigma, 0.0);
}

TEST(RangeNoise, TooFewReadingsGiveNoEstimate) {
  LadarScan scan = Cast(kStations[0], 2048, 2.0 * kPi, 0.044, 0.0, 1);
  for (size_t i = 0; i < scan.ranges.size(); ++i)
    if (i % 50 > 2) scan.ranges[i] = std::nanf("");  // runs of 3 valid readings: one triple each
  const RangeNoise m = MeasureRangeNoise(scan);
  EXPECT_LT(m.triples, kMinRangeNoiseTriples);
  EXPECT_EQ(m.sigma, 0.0);
}

}  // namespace
}  // namespace minenav
