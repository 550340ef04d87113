// contour_mapper over a real survey log made by log_tool: the refined poses must match
// the survey's truth, the map must be a valid contour-map JSON lying on the walls, and
// bad input must give exit code 2 with no output file. A batch run stopped by SIGTERM exits
// 130 within a second or two, keeping what it did in FILE.partial only; an output naming an
// input is refused (exit 2) and the input is left as it was.

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "common/config.h"
#include "common/file_io.h"
#include "mapper/contour_map_io.h"
#include "evaluation/map_evaluation.h"
#include "tests/child_process.h"
#include "tests/sanitizer.h"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

namespace fs = std::filesystem;
using testing::ChildProcess;
using testing::ReadTextFile;

int RunProcess(const std::vector<std::string>& argv, const fs::path& output) {
  return testing::RunProgram(argv.front(), {argv.begin() + 1, argv.end()}, output.string(), 300.0).exit_code;
}

class ContourMapperProcessTest : public ::testing::Test {
 protected:
  const testing::TempDir temp_{"contour_mapper_test"};
  const fs::path dir_ = temp_.path();
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
  int inserted = 0;
  for (const auto& e : est) {
    ASSERT_TRUE(truth_by_utime.count(e.utime)) << "pose with a utime of no scan: " << e.utime;
    // Issue 18: every row says what it is; the mapper writes only scans it inserted or tracked.
    EXPECT_TRUE(e.status == PoseStatus::kInserted || e.status == PoseStatus::kTracked) << e.utime;
    inserted += e.status == PoseStatus::kInserted;
    const Pose2 rel_est = Between(est0, e.pose);
    const Pose2 rel_true = Between(tru0, truth_by_utime.at(e.utime));
    worst_position = std::max(worst_position, TranslationDistance(rel_est, rel_true));
    worst_heading = std::max(worst_heading, HeadingDistance(rel_est, rel_true));
  }
  EXPECT_LT(worst_position, 0.05) << ReadTextFile((dir_ / "mapper.txt").string());
  EXPECT_LT(worst_heading, DegToRad(0.3));
  EXPECT_EQ(est.front().status, PoseStatus::kInserted);  // the first scan anchors the map
  EXPECT_GE(inserted, 1);

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

// Issue 11, item 7: --load-map of a 66-byte map with one 20 km segment took 6 GB and 18-39 s
// before bad_alloc (exit 3). Now: exit 2 at once, one line naming the contour and segment.
TEST_F(ContourMapperProcessTest, AMapWithA20KilometreSegmentIsRefusedAtOnce) {
  const fs::path map = dir_ / "forged.json";
  std::ofstream(map) << R"({"contours": [{"points": [[0, 0], [20000, 20000]]}]})";
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(RunProcess({MINENAV_CONTOUR_MAPPER_BIN, "--load-map", map.string(), "--log", (dir_ / "none.lcm").string(),
                        "--map-out", (dir_ / "out.json").string()},
                       dir_ / "out.txt"),
            2);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 2.0 * testing::kSlowdown);
  const auto lines = testing::LinesContaining(ReadTextFile((dir_ / "out.txt").string()), "error");
  ASSERT_EQ(lines.size(), 1u) << ReadTextFile((dir_ / "out.txt").string());
  EXPECT_NE(lines[0].find("forged.json: contour 0: segment 0 is 28284.3 m long, more than the 1000 m"),
            std::string::npos)
      << lines[0];
  EXPECT_FALSE(fs::exists(dir_ / "out.json"));
}

// A survey log of the first 20 stations of the synthetic mine with 2048-point scans: about
// 4 s of inserts and 2 s of final refinement in batch (RelWithDebInfo), long enough to be
// signalled in the middle of either. Made once for the tests below.
class ContourMapperSignalTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    temp_ = new testing::TempDir("contour_mapper_signal_test");
    dir_ = &temp_->path();
    const fs::path world = *dir_ / "mine.json", stations = *dir_ / "st.csv";
    ASSERT_EQ(RunProcess({MINENAV_LOG_TOOL_BIN, "generate", "--kind", "mine", "--seed", "2", "--world-out",
                          world.string(), "--stations-out", stations.string()},
                         *dir_ / "gen.txt"),
              0);
    auto all = LoadStationsCsv(stations.string());
    ASSERT_GE(all.size(), 20u);
    all.resize(20);
    SaveStationsCsv(stations.string(), all);
    ASSERT_EQ(RunProcess({MINENAV_LOG_TOOL_BIN, "survey", "--world", world.string(), "--stations", stations.string(),
                          "--sensor", "typhoon", "--points", "2048", "--pose-noise", "0.2,0.2,2deg", "--seed", "5",
                          "--out", Log(), "--truth-out", (*dir_ / "truth.csv").string()},
                         *dir_ / "survey.txt"),
              0)
        << ReadTextFile((*dir_ / "survey.txt").string());
  }
  static void TearDownTestSuite() {
    delete temp_;
    temp_ = nullptr;
    dir_ = nullptr;
  }
  static std::string Log() { return (*dir_ / "survey.lcm").string(); }
  static std::string Path(const std::string& name) { return (*dir_ / name).string(); }

  // Starts a batch run over the log, waits until its stderr contains `cue`, sends SIGTERM
  // and returns the exit code and the seconds from the signal to the exit.
  static std::pair<int, double> InterruptAt(const std::vector<std::string>& extra, const std::string& cue,
                                            const std::string& output) {
    std::vector<std::string> argv = {MINENAV_CONTOUR_MAPPER_BIN, "--log", Log()};
    argv.insert(argv.end(), extra.begin(), extra.end());
    ChildProcess p(argv, output);
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(300);
    while (ReadTextFile(output).find(cue) == std::string::npos && p.Running() &&
           std::chrono::steady_clock::now() < give_up)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    EXPECT_TRUE(p.Running()) << "ended before '" << cue << "': " << ReadTextFile(output);
    const auto signalled = std::chrono::steady_clock::now();
    p.Signal(SIGTERM);
    const auto code = p.Wait(60.0);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count();
    RecordProperty("milliseconds_from_signal_to_exit", static_cast<int>(1000 * seconds));
    return {code ? *code : -1, seconds};
  }

  // The poses kept, relative to the first, against the truth: what was mapped is right.
  static void ExpectPosesMatchTruth(const std::string& poses_csv) {
    const auto est = LoadPosesCsv(poses_csv);
    std::map<int64_t, Pose2> truth;
    for (const auto& t : LoadPosesCsv(Path("truth.csv"))) truth[t.utime] = t.pose;
    ASSERT_FALSE(est.empty());
    const Pose2 est0 = est.front().pose, tru0 = truth.at(est.front().utime);
    for (const auto& e : est) {
      ASSERT_TRUE(truth.count(e.utime)) << e.utime;
      EXPECT_LT(TranslationDistance(Between(est0, e.pose), Between(tru0, truth.at(e.utime))), 0.05) << e.utime;
    }
  }

  static testing::TempDir* temp_;
  static const fs::path* dir_;
};
testing::TempDir* ContourMapperSignalTest::temp_ = nullptr;
const fs::path* ContourMapperSignalTest::dir_ = nullptr;

// Issue 11, item 12: SIGTERM at scan 6 of 20, while periodic refinements run. Before: exit 0
// with the map, poses and SVG of 6 scans under the final names, as if complete.
TEST_F(ContourMapperSignalTest, SigtermMidLogKeepsPartialOutputsAndExits130) {
  const std::string map = Path("a_map.json"), poses = Path("a_poses.csv"), svg = Path("a_map.svg"),
                    out_log = Path("a_out.lcm"), output = Path("a.txt");
  const auto [code, seconds] = InterruptAt({"--map-out", map, "--poses-out", poses, "--svg-out", svg, "--log-out",
                                            out_log, "--refine-every-inserts", "2"},
                                           "scan 6,", output);
  const std::string log = ReadTextFile(output);
  EXPECT_EQ(code, kExitInterrupted) << log;
  EXPECT_LT(seconds, 2.0 * testing::kSlowdown) << log;
  for (const std::string& f : {map, poses, svg, out_log}) {
    EXPECT_FALSE(fs::exists(f)) << f << " written as if the run were complete";
    EXPECT_TRUE(fs::exists(f + ".partial")) << f << ".partial missing: " << log;
  }
  // One line says what was kept, and where.
  const auto lines = testing::LinesContaining(log, "interrupted before the end of the log: kept");
  ASSERT_EQ(lines.size(), 1u) << log;
  EXPECT_NE(lines[0].find("without the final refinement"), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find(map + ".partial"), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find(poses + ".partial"), std::string::npos) << lines[0];
  EXPECT_TRUE(testing::LinesContaining(log, "final refinement:").empty()) << log;
  // What was kept is a valid map and the poses of the scans mapped so far, on the truth.
  EXPECT_GE(mapper::LoadContourMapJson(map + ".partial").NumContours(), 1);
  const size_t kept = LoadPosesCsv(poses + ".partial").size();
  EXPECT_GE(kept, 6u);
  EXPECT_LT(kept, 20u);
  EXPECT_NE(lines[0].find("kept " + std::to_string(kept) + " inserted"), std::string::npos) << lines[0];
  ExpectPosesMatchTruth(poses + ".partial");
  EXPECT_NE(ReadTextFile(svg + ".partial").find("<svg"), std::string::npos);
}

// SIGTERM once every scan is in, during the final refinement (2 s here; minutes on a long
// log): it stops within a step and the unrefined result is kept as partial. Before: the
// refinement ran to its end and the outputs were written under the final names, exit 0.
TEST_F(ContourMapperSignalTest, SigtermInTheFinalRefinementStopsItAndKeepsPartialOutputs) {
  const std::string map = Path("b_map.json"), poses = Path("b_poses.csv"), output = Path("b.txt");
  const auto [code, seconds] =
      InterruptAt({"--map-out", map, "--poses-out", poses}, "20 scans received:", output);
  const std::string log = ReadTextFile(output);
  EXPECT_EQ(code, kExitInterrupted) << log;
  EXPECT_LT(seconds, 2.0 * testing::kSlowdown) << log;
  EXPECT_FALSE(fs::exists(map));
  EXPECT_FALSE(fs::exists(poses));
  EXPECT_EQ(LoadPosesCsv(poses + ".partial").size(), 20u) << log;
  EXPECT_EQ(testing::LinesContaining(log, "without the final refinement").size(), 1u) << log;
  ExpectPosesMatchTruth(poses + ".partial");
}

// Issue 11, item 13: an output equal to an input. Before, --map-out equal to --log wrote the
// map over the log it had just read (exit 0); now exit 2 before reading, the input intact.
TEST_F(ContourMapperSignalTest, AnOutputNamingAnInputIsRefusedAndTheInputKept) {
  const std::string copy = Path("copy.lcm"), map = Path("c_map.json");
  fs::copy_file(Log(), copy);
  const std::string before = ReadTextFile(copy);
  ASSERT_GT(before.size(), 100000u);
  mapper::ContourMap small;
  small.Create({{0, 0}, {1, 0}, {1, 1}});
  mapper::SaveContourMapJson(map, small);
  const std::string map_before = ReadTextFile(map);
  const std::string same_log_spelled_otherwise = (fs::path(copy).parent_path() / "." / "copy.lcm").string();
  const std::vector<std::vector<std::string>> cases = {
      {"--log", copy, "--map-out", copy},
      {"--log", copy, "--map-out", map, "--poses-out", same_log_spelled_otherwise},
      {"--log", copy, "--map-out", map, "--svg-out", copy},
      {"--log", copy, "--map-out", Path("d_map.json"), "--save-map", copy},
      {"--log", copy, "--map-out", Path("d_map.json"), "--load-map", map, "--save-map", map},
      {"--log", copy, "--load-map", map, "--map-out", map},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    std::vector<std::string> argv = {MINENAV_CONTOUR_MAPPER_BIN};
    argv.insert(argv.end(), cases[i].begin(), cases[i].end());
    const std::string output = Path("c" + std::to_string(i) + ".txt");
    EXPECT_EQ(RunProcess(argv, output), 2) << i << ": " << ReadTextFile(output);
    const auto lines = testing::LinesContaining(ReadTextFile(output), "refusing to overwrite it");
    EXPECT_EQ(lines.size(), 1u) << i << ": " << ReadTextFile(output);
    EXPECT_TRUE(ReadTextFile(copy) == before) << i << ": the log was changed";
    EXPECT_TRUE(ReadTextFile(map) == map_before) << i << ": the loaded map was changed";
  }
  EXPECT_FALSE(fs::exists(Path("d_map.json")));
}

}  // namespace
// Issue 12: `preset = carmen` in a config file showed under --print-config while the mapper
// kept the survey values (the preset was read from the command line only).
TEST_F(ContourMapperProcessTest, APresetInAConfigFileIsInForce) {
  const fs::path conf = dir_ / "carmen.conf";
  std::ofstream(conf) << "preset = carmen\n";
  auto printed = [&](const std::vector<std::string>& extra, const std::string& name) {
    std::vector<std::string> argv = {MINENAV_CONTOUR_MAPPER_BIN, "--print-config"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    EXPECT_EQ(RunProcess(argv, dir_ / name), 0);
    return ReadTextFile((dir_ / name).string());
  };
  const std::string from_file = printed({"--config", conf.string()}, "file.txt");
  EXPECT_NE(from_file.find("preset = carmen"), std::string::npos) << from_file;
  EXPECT_NE(from_file.find("max_odometry_gap = 5"), std::string::npos) << from_file;   // carmen's, not 1
  EXPECT_NE(from_file.find("final_refinement_rounds = 0"), std::string::npos) << from_file;
  // The same as the preset on the command line; a flag still overrides the preset.
  EXPECT_EQ(printed({"--preset", "carmen"}, "flag.txt"), from_file);
  const std::string overridden = printed({"--config", conf.string(), "--max-odometry-gap", "2"}, "override.txt");
  EXPECT_NE(overridden.find("max_odometry_gap = 2"), std::string::npos) << overridden;
}

// The nested keys a preset sets show under --print-config with the preset's values, from the
// command line as from a config file (the node test checks they are in force).
TEST_F(ContourMapperProcessTest, APresetsNestedValuesShowInThePrintedConfiguration) {
  const fs::path out = dir_ / "carmen.txt";
  ASSERT_EQ(RunProcess({MINENAV_CONTOUR_MAPPER_BIN, "--preset", "carmen", "--print-config"}, out), 0);
  const std::string config = ReadTextFile(out.string());
  EXPECT_NE(config.find("\nmapper.preprocessing.discontinuity_angle = 0.1745329252\n"), std::string::npos) << config;
  EXPECT_NE(config.find("\nmapper.pose.final_threshold = 0.05\n"), std::string::npos) << config;
  EXPECT_NE(config.find("\nmapper.min_scan_points = 30\n"), std::string::npos) << config;
  EXPECT_NE(config.find("\ninsert_min_translation = 0.3\n"), std::string::npos) << config;
  // A flag (here through its flat alias) overrides the preset.
  ASSERT_EQ(RunProcess({MINENAV_CONTOUR_MAPPER_BIN, "--preset", "carmen", "--max-correction-translation", "0.5",
                        "--print-config"},
                       out),
            0);
  EXPECT_NE(ReadTextFile(out.string()).find("\nmapper.max_correction_translation = 0.5\n"), std::string::npos);
  EXPECT_EQ(RunProcess({MINENAV_CONTOUR_MAPPER_BIN, "--preset", "mine", "--print-config"}, out), 2);
  EXPECT_NE(ReadTextFile(out.string()).find("survey, carmen"), std::string::npos) << ReadTextFile(out.string());
}

}  // namespace minenav
