// contour_mapper over a real survey log made by log_tool: the refined poses must match
// the survey's truth, the map must be a valid contour-map JSON lying on the walls, and
// bad input must give exit code 2 with no output file.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "common/file_io.h"
#include "mapper/contour_map_io.h"
#include "mapper/map_evaluation.h"
#include "tests/child_process.h"

namespace minenav {
namespace {

namespace fs = std::filesystem;
using testing::ChildProcess;
using testing::ReadTextFile;

int RunProcess(const std::vector<std::string>& argv, const fs::path& output) {
  ChildProcess p(argv, output.string());
  const auto code = p.Wait(300.0);
  return code ? *code : -1;
}

class ContourMapperProcessTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("contour_mapper_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(ContourMapperProcessTest, MapsASurveyLogToTruth) {
  const fs::path world = dir_ / "mine.json", stations = dir_ / "st.csv", log = dir_ / "survey.lcm",
                 truth = dir_ / "truth.csv", map = dir_ / "map.json", poses = dir_ / "poses.csv",
                 svg = dir_ / "map.svg";
  ASSERT_EQ(RunProcess({MINENAV_LOG_TOOL_BIN, "generate", "--kind", "mine", "--seed", "2", "--world-out",
                        world.string(), "--stations-out", stations.string()},
                dir_ / "gen.txt"),
            0)
      << ReadTextFile((dir_ / "gen.txt").string());
  // A short stretch of the 42-station route (about 4.8 m apart): its first 12 stations.
  {
    auto all = LoadStationsCsv(stations.string());
    ASSERT_GE(all.size(), 12u);
    all.resize(12);
    SaveStationsCsv(stations.string(), all);
  }
  ASSERT_EQ(RunProcess({MINENAV_LOG_TOOL_BIN, "survey", "--world", world.string(), "--stations", stations.string(),
                 "--sensor", "typhoon", "--points", "2048", "--pose-noise", "0.2,0.2,2deg", "--seed", "5",
                 "--out", log.string(), "--truth-out", truth.string()},
                dir_ / "survey.txt"),
            0)
      << ReadTextFile((dir_ / "survey.txt").string());
  ASSERT_EQ(RunProcess({MINENAV_CONTOUR_MAPPER_BIN, "--log", log.string(), "--map-out", map.string(), "--poses-out",
                 poses.string(), "--svg-out", svg.string()},
                dir_ / "mapper.txt"),
            0)
      << ReadTextFile((dir_ / "mapper.txt").string());

  // The first scan anchors the map at its initial estimate, so compare motion relative
  // to it: each refined pose expressed in the first one's frame against the same for truth.
  const auto est = LoadPosesCsv(poses.string());
  const auto tru = LoadPosesCsv(truth.string());
  std::map<int64_t, Pose2> truth_by_utime;
  for (const auto& t : tru) truth_by_utime[t.utime] = t.pose;
  ASSERT_GE(est.size(), 10u) << ReadTextFile((dir_ / "mapper.txt").string());
  const Pose2 est0 = est.front().pose, tru0 = truth_by_utime.at(est.front().utime);
  double worst_position = 0, worst_heading = 0;
  for (const auto& e : est) {
    ASSERT_TRUE(truth_by_utime.count(e.utime)) << "pose with a utime of no scan: " << e.utime;
    const Pose2 rel_est = Between(est0, e.pose);
    const Pose2 rel_true = Between(tru0, truth_by_utime.at(e.utime));
    worst_position = std::max(worst_position, TranslationDistance(rel_est, rel_true));
    worst_heading = std::max(worst_heading, HeadingDistance(rel_est, rel_true));
  }
  EXPECT_LT(worst_position, 0.05) << ReadTextFile((dir_ / "mapper.txt").string());
  EXPECT_LT(worst_heading, DegToRad(0.3));

  const auto contour_map = mapper::LoadContourMapJson(map.string());
  EXPECT_GE(contour_map.contours().size(), 1u);
  EXPECT_NE(ReadTextFile(svg.string()).find("<svg"), std::string::npos);
}

TEST_F(ContourMapperProcessTest, BadInputExitsTwoWithoutOutput) {
  const fs::path map = dir_ / "map.json", garbage = dir_ / "garbage.lcm";
  std::ofstream(garbage) << "this is not an LCM log";
  EXPECT_EQ(RunProcess({MINENAV_CONTOUR_MAPPER_BIN, "--log", garbage.string()}, dir_ / "a.txt"), 2);  // no --map-out
  EXPECT_NE(ReadTextFile((dir_ / "a.txt").string()).find("--map-out"), std::string::npos);
  EXPECT_EQ(RunProcess({MINENAV_CONTOUR_MAPPER_BIN, "--checkpoint-every", "3"}, dir_ / "e.txt"), 2);
  EXPECT_NE(ReadTextFile((dir_ / "e.txt").string()).find("--checkpoint"), std::string::npos);
  // A checkpoint that is not one, a map that does not exist: named, exit 2, nothing written.
  EXPECT_EQ(RunProcess({MINENAV_CONTOUR_MAPPER_BIN, "--checkpoint", garbage.string(), "--map-out", map.string()},
                       dir_ / "f.txt"),
            2);
  EXPECT_NE(ReadTextFile((dir_ / "f.txt").string()).find("not a contour-mapper checkpoint"), std::string::npos);
  EXPECT_EQ(RunProcess({MINENAV_CONTOUR_MAPPER_BIN, "--load-map", (dir_ / "nomap.json").string()}, dir_ / "g.txt"), 2);
  EXPECT_NE(ReadTextFile((dir_ / "g.txt").string()).find("nomap.json"), std::string::npos);
  EXPECT_EQ(RunProcess({MINENAV_CONTOUR_MAPPER_BIN, "--log", (dir_ / "missing.lcm").string(), "--map-out", map.string()},
                dir_ / "b.txt"),
            2);
  EXPECT_EQ(RunProcess({MINENAV_CONTOUR_MAPPER_BIN, "--log", garbage.string(), "--map-out", map.string()}, dir_ / "c.txt"),
            2);
  EXPECT_EQ(RunProcess({MINENAV_CONTOUR_MAPPER_BIN, "--log", garbage.string(), "--bogus", "1"}, dir_ / "d.txt"), 2);
  EXPECT_FALSE(fs::exists(map));
  EXPECT_NE(ReadTextFile((dir_ / "b.txt").string()).find("missing.lcm"), std::string::npos);
}

}  // namespace
}  // namespace minenav
