#include "common/config.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "common/angle.h"
#include "common/config_testing.h"
#include "tests/temp_dir.h"

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

// A new file in this binary's temporary folder (removed when the binary exits).
std::string WriteTemp(const std::string& content) {
  static int count = 0;
  const std::string name = testing::TempPath("config_" + std::to_string(count++) + ".conf");
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

// Issue 16 (fuzz target config): a help text spanning lines (the contour mapper's
// worker_queue_capacity) made --print-config write a line that is neither a comment nor
// `key = value`, so the printed configuration did not read back.
TEST(ConfigTest, PrintedConfigWithAMultiLineHelpReadsBack) {
  auto declare = [](ConfigSchema& s, double* queue, int* points) {
    s.AddDouble("queue", queue, "s", "how long scans wait\n(a full queue drops the oldest)\nat most", 0.0, 100.0);
    s.AddInt("points", points, "readings per scan");
  };
  double queue_a = 7.5;
  int points_a = 3;
  ConfigSchema a("test", "test");
  declare(a, &queue_a, &points_a);
  const std::string text = a.ConfigText();
  EXPECT_NE(text.find("# (a full queue drops the oldest)\n"), std::string::npos) << text;
  double queue_b = 0.0;
  int points_b = 0;
  ConfigSchema b("test", "test");
  declare(b, &queue_b, &points_b);
  ASSERT_NO_THROW(b.LoadText(text, "printed")) << text;
  EXPECT_DOUBLE_EQ(queue_b, 7.5);
  EXPECT_EQ(points_b, 3);
}

TEST(ConfigTest, NumberLists) {
  const auto v = ParseNumberList("0.33,0.33,3.33deg", "--pose-noise", 3);
  EXPECT_DOUBLE_EQ(v[0], 0.33);
  EXPECT_NEAR(v[2], DegToRad(3.33), 1e-12);
  EXPECT_THROW(ParseNumberList("1,2", "--pose-noise", 3), UsageError);
  EXPECT_THROW(ParseNumberList("1,x,2", "--pose-noise", 3), UsageError);
}

// A library's options struct declared through a scope, placed by the process under "pose".
struct MatchOptionsForTest {
  double final_threshold = 0.1;
  int max_iterations = 30;
};
void DeclareOptions(OptionScope scope, MatchOptionsForTest& o) {
  scope.AddDouble("final_threshold", &o.final_threshold, "m", "last correspondence threshold", 0.0, 10.0);
  scope.AddInt("max_iterations", &o.max_iterations, "Gauss-Newton iterations", 1, 1000);
}

TEST(OptionScopeTest, NestedKeysAreReachableFromFileAndFlags) {
  MatchOptionsForTest pose, refine;
  ConfigSchema s("prog", "test program");
  DeclareOptions(OptionScope(s).Nested("pose"), pose);
  DeclareOptions(OptionScope(s).Nested("mapper").Nested("refine"), refine);
  const std::string file = WriteTemp("pose.final_threshold = 0.25\nmapper.refine.max_iterations = 7\n");
  ASSERT_EQ(s.Parse({"--config", file, "--pose.max-iterations", "12", "--mapper.refine.final_threshold=0.5"}),
            ParseOutcome::kRun);
  EXPECT_DOUBLE_EQ(pose.final_threshold, 0.25);
  EXPECT_EQ(pose.max_iterations, 12);
  EXPECT_DOUBLE_EQ(refine.final_threshold, 0.5);
  EXPECT_EQ(refine.max_iterations, 7);
  EXPECT_TRUE(s.WasSet("mapper.refine.max_iterations"));
  EXPECT_FALSE(s.WasSet("max_iterations"));
  // Errors name the whole key; a bare inner name is unknown.
  try {
    s.Parse({"--pose.final-threshold", "11"});
    FAIL() << "out of range accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("pose.final_threshold"), std::string::npos) << e.what();
  }
  EXPECT_THROW(s.Parse({"--final-threshold", "0.2"}), UsageError);
  const std::string config = s.ConfigText();
  EXPECT_NE(config.find("\nmapper.refine.final_threshold = 0.5\n"), std::string::npos) << config;
  std::remove(file.c_str());
}

TEST(OptionScopeTest, AnAliasSetsItsKeyAndOnlyTheKeyIsPrinted) {
  MatchOptionsForTest pose;
  ConfigSchema s("prog", "test program");
  const OptionScope scope = OptionScope(s).Nested("pose");
  DeclareOptions(scope, pose);
  scope.AddAlias("final_threshold", "final_threshold");
  ASSERT_EQ(s.Parse({"--final-threshold", "0.3"}), ParseOutcome::kRun);
  EXPECT_DOUBLE_EQ(pose.final_threshold, 0.3);
  EXPECT_TRUE(s.WasSet("pose.final_threshold"));
  const std::string file = WriteTemp("final_threshold = 0.4\n");
  ASSERT_EQ(s.Parse({"--config", file}), ParseOutcome::kRun);
  EXPECT_DOUBLE_EQ(pose.final_threshold, 0.4);
  EXPECT_NE(s.HelpText().find("--pose.final-threshold     (also --final-threshold) last correspondence threshold [m]"), std::string::npos)
      << s.HelpText();
  EXPECT_EQ(s.ConfigText().find("\nfinal_threshold ="), std::string::npos) << s.ConfigText();
  EXPECT_THROW(scope.AddAlias("pose.max_iterations", "final_threshold"), std::logic_error);
  EXPECT_THROW(scope.AddAlias("x", "no_such_option"), std::logic_error);
  std::remove(file.c_str());
}

TEST(OptionScopeTest, TheOptionsTableHasARowPerKeyWithUnitAndDefault) {
  Options o;
  auto s = MakeSchema(&o);
  const std::string table = s.OptionsTable();
  EXPECT_EQ(table.rfind("| key | unit | default | meaning |\n|---|---|---|---|\n", 0), 0u) << table;
  EXPECT_NE(table.find("| `speed` | m/s | `0.076` | cruise speed |\n"), std::string::npos) << table;
  EXPECT_NE(table.find("| `sensor` | typhoon\\|cyclone | `typhoon` | sensor model |\n"), std::string::npos) << table;
  EXPECT_NE(table.find("| `scan_channel` | publishes ladar_scan_t | `LADAR_SCAN` | scans |\n"), std::string::npos)
      << table;
  size_t rows = 0;
  for (char c : table) rows += c == '\n';
  EXPECT_EQ(rows, 2u + 6u);
}

TEST(OptionScopeTest, LoadTextNamesItsSourceInErrors) {
  Options o;
  auto s = MakeSchema(&o);
  try {
    s.LoadText("speed = 0.5\npoints = 99999\n", "preset fast");
    FAIL() << "out of range accepted";
  } catch (const UsageError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("preset fast:2: points", 0), 0u) << e.what();
  }
  EXPECT_DOUBLE_EQ(o.speed, 0.5);  // the lines before the bad one are in force
}



// An enum and a duration as a library declares them (issue 12: options as data).
enum class ShapeForTest { kLine, kArc };
const char* ToString(ShapeForTest s) { return s == ShapeForTest::kLine ? "line" : "arc"; }
struct PathOptionsForTest {
  ShapeForTest shape = ShapeForTest::kLine;
  int64_t history_us = 5'000'000;
};
void DeclareOptions(OptionScope scope, PathOptionsForTest& o) {
  scope.AddEnum("shape", &o.shape, "path shape", {ShapeForTest::kLine, ShapeForTest::kArc});
  scope.AddMicroseconds("history", &o.history_us, "truth kept", 0.1, 600.0);
}

TEST(OptionScopeTest, EnumsAreNamedByToStringAndDurationsAreSecondsKeptInMicroseconds) {
  PathOptionsForTest o;
  ConfigSchema s("prog", "test program");
  DeclareOptions(OptionScope(s).Nested("path"), o);
  EXPECT_EQ(ValueInConfigText(s.ConfigText(), "path.shape"), "line");
  EXPECT_EQ(ValueInConfigText(s.ConfigText(), "path.history"), "5");
  ASSERT_EQ(s.Parse({"--path.shape", "arc", "--path.history", "0.25"}), ParseOutcome::kRun);
  EXPECT_EQ(o.shape, ShapeForTest::kArc);
  EXPECT_EQ(o.history_us, 250'000);
  EXPECT_THROW(s.Parse({"--path.shape", "circle"}), UsageError);
  EXPECT_THROW(s.Parse({"--path.history", "0.01"}), UsageError);  // below 0.1 s
  EXPECT_NE(s.OptionsTable().find("| `path.shape` | line\\|arc | `line` | path shape |"), std::string::npos)
      << s.OptionsTable();
  EXPECT_NE(s.OptionsTable().find("| `path.history` | s | `5` | truth kept |"), std::string::npos);
  const std::vector<ConfigSchema::OptionInfo> options = s.Options();
  ASSERT_EQ(options.size(), 2u);
  EXPECT_EQ(options[0].choices, (std::vector<std::string>{"line", "arc"}));
  EXPECT_EQ(options[1].kind, "number");
}

TEST(OptionScopeTest, TheReachabilityCheckSetsEveryKeyAndFindsItInTheStruct) {
  const std::vector<std::string> keys = ExpectEveryOptionReachable<PathOptionsForTest>();
  EXPECT_EQ(keys, (std::vector<std::string>{"shape", "history"}));
  const auto match_keys = ExpectEveryOptionReachable<MatchOptionsForTest>();
  EXPECT_EQ(match_keys.size(), 2u);  // MatchOptionsForTest: 2 fields
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
  const std::string path = testing::TempPath("peek_option.conf");
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
