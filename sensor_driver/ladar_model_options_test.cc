// The sensor model as options (issue 12): every field declared and reachable, the presets
// with their overrides, errors that name the option.

#include "sensor_driver/ladar_model_options.h"

#include <gtest/gtest.h>

#include "common/angle.h"
#include "common/config_testing.h"
#include "sensor_driver/scan_schedule.h"

namespace minenav {
namespace {

TEST(LadarModelOptionsTest, EveryFieldIsDeclaredAndReachable) {
  // LadarModelOptions: sensor, points and an override for each of LadarModel's other 12
  // parameters (sensor_id, the ranges, angles, resolutions, noise, divergences, mixed pixels,
  // scan rate).
  EXPECT_EQ(ExpectEveryOptionReachable<LadarModelOptions>().size(), 14u);
  // ScanScheduleOptions: history and max_gap; period_us is 1 / the model's scan rate, not an option.
  EXPECT_EQ(ExpectEveryOptionReachable<ScanScheduleOptions>().size(), 2u);
}

TEST(LadarModelOptionsTest, NoOverrideIsThePreset) {
  const LadarModel typhoon = BuildLadarModel(LadarModelOptions());
  const LadarModel expected = LadarModel::Typhoon();
  EXPECT_EQ(typhoon.sensor_id, expected.sensor_id);
  EXPECT_EQ(typhoon.num_points, expected.num_points);
  EXPECT_EQ(typhoon.range_sigma, expected.range_sigma);
  EXPECT_EQ(typhoon.scan_rate, expected.scan_rate);
  LadarModelOptions o;
  o.sensor = "cyclone";
  o.points = 8192;
  const LadarModel cyclone = BuildLadarModel(o);
  EXPECT_EQ(cyclone.num_points, 8192);
  EXPECT_EQ(cyclone.scan_rate, LadarModel::Cyclone(8192).scan_rate);
  EXPECT_EQ(cyclone.mixed_pixel_probability, LadarModel::Cyclone(8192).mixed_pixel_probability);
}

TEST(LadarModelOptionsTest, OverridesReplaceThePresetsValues) {
  LadarModelOptions o;
  o.points = 1024;  // a Typhoon with other points: 2 pi / points
  o.sensor_id = "front";
  o.range_sigma = "0.05";
  o.start_angle = "-180deg";
  o.beam_divergence_vertical = "0.002";
  o.scan_rate = "5";
  const LadarModel m = BuildLadarModel(o);
  EXPECT_EQ(m.num_points, 1024);
  EXPECT_EQ(m.angular_resolution, 0.0);
  EXPECT_EQ(m.sensor_id, "front");
  EXPECT_DOUBLE_EQ(m.range_sigma, 0.05);
  EXPECT_NEAR(m.start_angle, -kPi, 1e-12);
  EXPECT_DOUBLE_EQ(m.beam_divergence_vertical, 0.002);
  EXPECT_DOUBLE_EQ(m.scan_rate, 5.0);
  EXPECT_DOUBLE_EQ(m.min_range, LadarModel::Typhoon().min_range);
}

TEST(LadarModelOptionsTest, ErrorsNameTheOptionAndItsFlag) {
  LadarModelOptions o;
  o.min_range = "far";
  try {
    BuildLadarModel(o, "model.");
    FAIL() << "accepted";
  } catch (const UsageError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("model.min_range (--min-range): 'far'", 0), 0u) << e.what();
  }
  o.min_range = "50";
  o.max_range = "10";
  try {
    BuildLadarModel(o);
    FAIL() << "accepted";
  } catch (const UsageError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("sensor model: max_range", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace minenav
