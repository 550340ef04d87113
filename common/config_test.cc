#include "common/config.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <cstdio>
#include <fstream>

#include "common/angle.h"

namespace minenav {
namespace {

struct Options {
  double speed = 0.076;
  double heading = 0.0;
  int points = 2048;
  bool verbose = false;
  std::string sensor = "typhoon";
  std::string channel = "LADAR_SCAN";
};

ConfigSchema MakeSchema(Options* o) {
  ConfigSchema s("prog", "test program");
  s.AddDouble("speed", &o->speed, "m/s", "cruise speed", 0.0, 1.0);
  s.AddDouble("heading", &o->heading, "rad", "start heading");
  s.AddInt("points", &o->points, "points per scan", 1, 8192);
  s.AddBool("verbose", &o->verbose, "talk more");
  s.AddString("sensor", &o->sensor, "sensor model", {"typhoon", "cyclone"});
  s.AddChannel("scan_channel", &o->channel, "publishes", "ladar_scan_t", "scans");
  return s;
}

std::string WriteTemp(const std::string& content) {
  char name[] = "/tmp/minenav_config_XXXXXX";
  const int fd = mkstemp(name);
  EXPECT_GE(fd, 0);
  close(fd);
  std::ofstream(name) << content;
  return name;
}

TEST(ConfigTest, DefaultsFileThenFlags) {
  Options o;
  auto s = MakeSchema(&o);
  const std::string file = WriteTemp("# comment\nspeed = 0.5\npoints = 512  # trailing\nsensor = cyclone\n");
  ASSERT_EQ(s.Parse({"--points=1024", "--config", file, "--verbose", "--heading", "90deg"}), ParseOutcome::kRun);
  EXPECT_DOUBLE_EQ(o.speed, 0.5);
  EXPECT_EQ(o.points, 1024);  // flag beats file, wherever it stands
  EXPECT_EQ(o.sensor, "cyclone");
  EXPECT_TRUE(o.verbose);
  EXPECT_NEAR(o.heading, kPi / 2, 1e-12);
  std::remove(file.c_str());
}

TEST(ConfigTest, ErrorsNameKeyAndLine) {
  Options o;
  auto s = MakeSchema(&o);
  const std::string file = WriteTemp("speed = 0.5\nspeeed = 1\n");
  try {
    s.Parse({"--config", file});
    FAIL() << "unknown key accepted";
  } catch (const UsageError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(":2"), std::string::npos) << what;
    EXPECT_NE(what.find("speeed"), std::string::npos) << what;
  }
  std::remove(file.c_str());
  EXPECT_THROW(s.Parse({"--speed=2"}), UsageError);      // out of range
  EXPECT_THROW(s.Parse({"--points=abc"}), UsageError);   // not a number
  EXPECT_THROW(s.Parse({"--sensor=lidar"}), UsageError); // not a choice
  EXPECT_THROW(s.Parse({"--nope=1"}), UsageError);
  EXPECT_THROW(s.Parse({"stray"}), UsageError);
  EXPECT_THROW(s.Parse({"--scan-channel="}), UsageError);
}

TEST(ConfigTest, HelpListsChannelsAndDefaults) {
  Options o;
  auto s = MakeSchema(&o);
  const std::string help = s.HelpText();
  EXPECT_NE(help.find("Channels:"), std::string::npos);
  EXPECT_NE(help.find("publishes ladar_scan_t on 'LADAR_SCAN'"), std::string::npos);
  EXPECT_NE(help.find("--speed"), std::string::npos);
  EXPECT_NE(help.find("(default: 0.076)"), std::string::npos);
  EXPECT_NE(help.find("[m/s]"), std::string::npos);
}

TEST(ConfigTest, PrintedConfigReadsBackTheSame) {
  Options a;
  auto sa = MakeSchema(&a);
  sa.Parse({"--speed=0.25", "--points=99", "--sensor=cyclone"});
  const std::string file = WriteTemp(sa.ConfigText());
  Options b;
  auto sb = MakeSchema(&b);
  sb.Parse({"--config", file});
  EXPECT_DOUBLE_EQ(b.speed, 0.25);
  EXPECT_EQ(b.points, 99);
  EXPECT_EQ(b.sensor, "cyclone");
  std::remove(file.c_str());
}

TEST(ConfigTest, NumberLists) {
  const auto v = ParseNumberList("0.33,0.33,3.33deg", "--pose-noise", 3);
  EXPECT_DOUBLE_EQ(v[0], 0.33);
  EXPECT_NEAR(v[2], DegToRad(3.33), 1e-12);
  EXPECT_THROW(ParseNumberList("1,2", "--pose-noise", 3), UsageError);
  EXPECT_THROW(ParseNumberList("1,x,2", "--pose-noise", 3), UsageError);
}

}  // namespace
TEST(ConfigSchemaTest, WasSetTellsGivenKeysFromDefaults) {
  ConfigSchema schema("t", "test");
  int every = 10, other = 1;
  schema.AddInt("checkpoint_every", &every, "n");
  schema.AddInt("other", &other, "n");
  schema.Parse({"--checkpoint-every", "10"});
  EXPECT_TRUE(schema.WasSet("checkpoint_every"));  // given, even though equal to the default
  EXPECT_FALSE(schema.WasSet("other"));
}

// Issue 12: `preset = carmen` in a config file showed under --print-config while the mapper
// kept the survey values: the preset was read from the command line only.
TEST(ConfigSchemaTest, PeekOptionReadsTheCommandLineThenTheConfigFile) {
  const std::string path = (std::filesystem::temp_directory_path() / "minenav_peek_option.conf").string();
  std::ofstream(path) << "# a preset in a file\nsome_key = 3\npreset = carmen   # comment\n";
  EXPECT_EQ(PeekOption({"--config", path}, "preset").value_or(""), "carmen");
  EXPECT_EQ(PeekOption({"--config=" + path, "--preset", "survey"}, "preset").value_or(""), "survey");
  EXPECT_EQ(PeekOption({"--preset=survey"}, "preset").value_or(""), "survey");
  EXPECT_FALSE(PeekOption({"--other", "1"}, "preset").has_value());
  EXPECT_EQ(PeekOption({"--max-odometry-gap", "2"}, "max_odometry_gap").value_or(""), "2");
  EXPECT_THROW(PeekOption({"--config", path + ".missing"}, "preset"), UsageError);
  std::filesystem::remove(path);
}

}  // namespace minenav
