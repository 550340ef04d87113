// log_tool as users run it: the documented survey example, round trips through export,
// and every kind of bad input: exit code 2, one line on stderr, no output file left.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/file_io.h"
#include "common/node/conversions.h"
#include "common/node/event_log.h"
#include "logger/log_tool_run.h"
#include "logger/run_log.h"
#include "logger/test_logs.h"

namespace minenav {
namespace {

using logger_test::FileExists;
using logger_test::ReadAll;
using logger_test::TempPath;

using logger_test::LogTool;
using logger_test::Quote;
using logger_test::RunResult;

// The files in a directory other than the given ones (temporary files left behind).
std::vector<std::string> FilesIn(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string Dir() { return std::filesystem::path(TempPath("x")).parent_path().string(); }

// Expects exit 2, exactly one line on stderr containing `needle`, and none of `outputs`.
void ExpectInputError(const RunResult& r, const std::string& needle, const std::vector<std::string>& outputs) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << "stderr: " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "stderr: " << r.err;
  for (const auto& o : outputs) EXPECT_FALSE(FileExists(o)) << o;
  for (const auto& f : FilesIn(Dir())) {
    EXPECT_EQ(f.find(".partial"), std::string::npos) << f;
    EXPECT_EQ(f.find(".tmp."), std::string::npos) << f;
  }
}

// Issue 16: a logger killed mid-write and restarted writes the next part; `join` keeps every
// whole event of every part, in order, drops the torn one and names it in one line.
TEST(LogToolCli, JoinKeepsTheWholeEventsOfEveryPartAndNamesATornEnd) {
  const std::string a = TempPath("mission.lcm.00"), b = TempPath("mission.lcm.01"), out = TempPath("joined.lcm");
  auto write_part = [](const std::string& path, int first, int count) {
    LogWriter w(path);
    for (int i = first; i < first + count; ++i) {
      const std::string payload = "event " + std::to_string(i);
      w.Write("CHANNEL_" + std::to_string(i % 3), 1000 * i, payload.data(), static_cast<int>(payload.size()));
    }
    w.Close();
  };
  write_part(a, 0, 10);
  write_part(b, 10, 5);
  // The first part's writer died in the middle of its last event.
  const std::string whole = ReadAll(a);
  { std::ofstream(a, std::ios::binary | std::ios::trunc) << whole.substr(0, whole.size() - 4); }
  const RunResult r = LogTool("join " + out + " " + a + " " + b);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(a + ": torn at its end"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the 9 whole events before it kept"), std::string::npos) << r.err;
  LogReader joined(out);
  std::vector<int> kept;
  while (auto e = joined.Next()) {
    const std::string text(e->data.begin(), e->data.end());
    const int i = std::stoi(text.substr(6));
    EXPECT_EQ(e->channel, "CHANNEL_" + std::to_string(i % 3));
    EXPECT_EQ(e->timestamp, 1000 * i);
    kept.push_back(i);
  }
  EXPECT_EQ(joined.truncation(), "");
  EXPECT_EQ(kept, (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 10, 11, 12, 13, 14}));
  // Damage inside a part (not at its end) is an error: no output.
  std::string damaged = ReadAll(b);
  damaged[damaged.size() / 2] = '\xff';
  damaged.replace(0, 4, "XXXX");  // the first event's sync word
  { std::ofstream(b, std::ios::binary | std::ios::trunc) << damaged; }
  const std::string out2 = TempPath("joined2.lcm");
  const RunResult bad = LogTool("join " + out2 + " " + b);
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_FALSE(FileExists(out2));
  EXPECT_EQ(LogTool("join " + a + " " + a).exit_code, 2);  // OUT is a part
}

// A small world and stations written by log_tool generate.
struct Inputs {
  std::string world, stations;
};
Inputs Generate(const std::string& kind = "mine", const std::string& extra = "--rows 1 --cols 2 --stations 8") {
  Inputs in{TempPath("world.json"), TempPath("stations.csv")};
  const RunResult r = LogTool("generate --kind " + kind + " --seed 3 " + extra + " --world-out " + in.world +
                              " --stations-out " + in.stations);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return in;
}

TEST(LogToolCli, TheDocumentedSurveyExampleWorks) {
  const Inputs in = Generate("mine", "");  // the full 2 x 3 panel with 42 stations
  const std::string log = TempPath("survey.lcm"), truth = TempPath("truth.csv");
  const RunResult r = LogTool("survey --world " + in.world + " --stations " + in.stations +
                              " --sensor typhoon --points 2048 --pose-noise 0.33,0.33,3.33deg --seed 7 --out " + log +
                              " --truth-out " + truth);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<StampedPose> truth_rows = LoadPosesCsv(truth);
  const std::vector<Station> stations = LoadStationsCsv(in.stations);
  ASSERT_EQ(truth_rows.size(), 42u);
  ASSERT_EQ(stations.size(), 42u);
  const RunLog run = ReadRunLog(log);
  const auto& scans = run.scans.at("LADAR_SCAN");
  const auto& sim_truth = run.tracks.at("SIM_TRUTH").poses;
  const auto& odometry = run.tracks.at("ODOMETRY").poses;
  ASSERT_EQ(scans.size(), 42u);
  ASSERT_EQ(sim_truth.size(), 42u);
  ASSERT_EQ(odometry.size(), 42u);
  double sum_dx2 = 0, sum_dth2 = 0;
  for (size_t k = 0; k < 42; ++k) {
    EXPECT_EQ(scans[k].ranges.size(), 2048u);
    EXPECT_EQ(scans[k].sensor_id, "typhoon");
    EXPECT_EQ(scans[k].scan_id, static_cast<int64_t>(k));
    // The utime ties scan, truth.csv row, SIM_TRUTH and ODOMETRY together.
    EXPECT_EQ(scans[k].utime, truth_rows[k].utime);
    EXPECT_EQ(sim_truth[k].utime, truth_rows[k].utime);
    EXPECT_EQ(odometry[k].utime, truth_rows[k].utime);
    if (k > 0) {
      EXPECT_EQ(scans[k].utime - scans[k - 1].utime, 1'000'000);
    }
    // SIM_TRUTH equals the station poses (CSV keeps 10 significant digits).
    EXPECT_NEAR(sim_truth[k].pose.x, stations[k].pose.x, 1e-9);
    EXPECT_NEAR(sim_truth[k].pose.y, stations[k].pose.y, 1e-9);
    EXPECT_NEAR(sim_truth[k].pose.theta, stations[k].pose.theta, 1e-9);
    EXPECT_NEAR(truth_rows[k].pose.x, stations[k].pose.x, 1e-9);
    sum_dx2 += std::pow(odometry[k].pose.x - sim_truth[k].pose.x, 2);
    sum_dth2 += std::pow(NormalizeAngle(odometry[k].pose.theta - sim_truth[k].pose.theta), 2);
  }
  // 42 samples: the RMS is within ~30% of sigma with overwhelming probability.
  EXPECT_NEAR(std::sqrt(sum_dx2 / 42), 0.33, 0.33 * 0.35);
  EXPECT_NEAR(std::sqrt(sum_dth2 / 42), 3.33 * kPi / 180, 3.33 * kPi / 180 * 0.35);

  // Round trip: export SIM_TRUTH gives truth.csv again.
  const std::string exported = TempPath("exported.csv");
  ASSERT_EQ(LogTool("export " + log + " --poses SIM_TRUTH --out " + exported).exit_code, 0);
  EXPECT_EQ(ReadAll(exported), ReadAll(truth));
  // Same seed, same bytes.
  const std::string again = TempPath("again.lcm");
  ASSERT_EQ(LogTool("survey --world " + in.world + " --stations " + in.stations +
                    " --sensor typhoon --points 2048 --pose-noise 0.33,0.33,3.33deg --seed 7 --quiet --out " + again)
                .exit_code,
            0);
  EXPECT_EQ(ReadAll(again), ReadAll(log));
}

TEST(LogToolCli, SensorFlagsOverrideTheModel) {
  const Inputs in = Generate();
  const std::string log = TempPath("s.lcm");
  const RunResult r = LogTool("survey --world " + in.world + " --stations " + in.stations +
                              " --sensor cyclone --points 512 --min-range 2 --max-range 20 --range-sigma 0 "
                              "--range-resolution 0 --start-angle 0.5 --mixed-pixel-probability 0 --out " + log);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const RunLog run = ReadRunLog(log);
  const LadarScan& s = run.scans.at("LADAR_SCAN")[0];
  EXPECT_EQ(s.sensor_id, "cyclone");
  EXPECT_EQ(s.ranges.size(), 512u);
  EXPECT_NEAR(s.min_range, 2.0, 1e-6);
  EXPECT_NEAR(s.max_range, 20.0, 1e-6);
  EXPECT_NEAR(s.start_angle, 0.5, 1e-6);
  EXPECT_NEAR(s.angle_step * 512, 2 * kPi, 1e-4);
  for (size_t i = 0; i < s.ranges.size(); ++i)
    if (s.IsValid(i)) {
      EXPECT_LE(s.ranges[i], 20.0f);
    }
}

TEST(LogToolCli, DriftAndSeveralWorlds) {
  const Inputs in = Generate();
  // Two worlds: the second station stands in world 1, a single wall 2 m ahead of it.
  const std::string stations = TempPath("st2.csv");
  std::ofstream(stations) << "x,y,theta,world\n3,3,0,0\n3,3,0,1\n";
  const std::string world1 = TempPath("w1.json");
  std::ofstream(world1) << R"({"segments": [[5, -10, 5, 10]]})";
  const std::string log = TempPath("w.lcm");
  const RunResult r = LogTool("survey --world " + in.world + " --world " + world1 + " --stations " + stations +
                              " --drift 0.02,0.5deg,0.01 --range-sigma 0 --range-resolution 0 --out " + log);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const RunLog run = ReadRunLog(log);
  const auto& scans = run.scans.at("LADAR_SCAN");
  EXPECT_NEAR(scans[1].ranges[0], 2.0, 1e-5);  // the wall at x = 5 ahead of (3, 3)
  EXPECT_NE(scans[0].ranges[0], scans[1].ranges[0]);
  // Drift: the first estimate is the truth.
  EXPECT_NEAR(run.tracks.at("ODOMETRY").poses[0].pose.x, 3.0, 1e-12);
}

TEST(LogToolCli, SurveyReadsAConfigFile) {
  const Inputs in = Generate();
  const std::string config = TempPath("survey.conf"), log = TempPath("c.lcm");
  std::ofstream(config) << "# a survey\nworld = " << in.world << "\nstations = " << in.stations
                        << "\nsensor = cyclone\npoints = 128\npose_noise = 0.1,0.1,1deg\n";
  const RunResult r = LogTool("survey --config " + config + " --points 64 --out " + log);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const RunLog run = ReadRunLog(log);
  EXPECT_EQ(run.scans.at("LADAR_SCAN")[0].sensor_id, "cyclone");
  EXPECT_EQ(run.scans.at("LADAR_SCAN")[0].ranges.size(), 64u);  // the flag overrides the file
}

TEST(LogToolCli, GenerateWritesEveryKind) {
  for (const std::string kind : {"mine", "research", "mockup", "loop"}) {
    const Inputs in = Generate(kind, "");
    EXPECT_GT(LoadSegmentsJson(in.world).size(), 20u) << kind;
    EXPECT_GE(LoadStationsCsv(in.stations).size(), 16u) << kind;
  }
}

TEST(LogToolCli, InfoExportRenderOnASmallLog) {
  const Inputs in = Generate();
  const std::string log = TempPath("s.lcm");
  ASSERT_EQ(LogTool("survey --world " + in.world + " --stations " + in.stations +
                    " --points 256 --pose-noise 0.1,0.1,2deg --out " + log)
                .exit_code,
            0);
  const RunResult info = LogTool("info " + log);
  EXPECT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("minenav.ladar_scan_t"), std::string::npos) << info.out;
  const RunResult json = LogTool("info --json " + log);
  EXPECT_NE(json.out.find("\"decode_errors\": 0"), std::string::npos) << json.out;

  const std::string scans_csv = TempPath("scans.csv");
  ASSERT_EQ(LogTool("export " + log + " --scans-out " + scans_csv).exit_code, 0);
  const std::string csv = ReadAll(scans_csv);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 8 * 256);

  const std::string svg = TempPath("run.svg");
  const RunResult render = LogTool("render " + log + " --world " + in.world + " --scans-at-odometry --out " + svg);
  ASSERT_EQ(render.exit_code, 0) << render.err;
  const std::string text = ReadAll(svg);
  EXPECT_NE(text.find("SIM_TRUTH (8)"), std::string::npos);
  EXPECT_NE(text.find("scan points at ODOMETRY poses"), std::string::npos);
}

TEST(LogToolCli, HelpForEverySubcommand) {
  for (const std::string sub : {"survey", "generate", "info", "export", "render", "record"}) {
    const RunResult r = LogTool(sub + " --help");
    EXPECT_EQ(r.exit_code, 0) << sub << ": " << r.err;
    EXPECT_NE(r.out.find("Usage: log_tool " + sub), std::string::npos) << r.out;
  }
  const RunResult survey = LogTool("survey --help --sensor cyclone");
  EXPECT_NE(survey.out.find("--range-sigma"), std::string::npos);
  EXPECT_NE(survey.out.find("(default: 0.1)"), std::string::npos) << "Cyclone defaults shown";
  EXPECT_EQ(LogTool("--help").exit_code, 0);
  EXPECT_EQ(LogTool("frobnicate").exit_code, 2);
}

// ---- bad input ----

TEST(LogToolBadInput, MalformedWorldJson) {
  const Inputs in = Generate();
  const std::string log = TempPath("o.lcm"), truth = TempPath("t.csv");
  const std::string args = " --stations " + in.stations + " --out " + log + " --truth-out " + truth;
  const std::string bad = TempPath("bad.json");
  std::ofstream(bad) << R"({"segments": [[0, 0, 1, 1], [0, 0, 1]]})";
  ExpectInputError(LogTool("survey --world " + bad + args), "segments[1] is not [x1, y1, x2, y2]", {log, truth});
  std::ofstream(bad) << "{\"segments\": [[0, 0, 1";
  ExpectInputError(LogTool("survey --world " + bad + args), "not valid JSON", {log, truth});
  std::ofstream(bad) << R"({"walls": []})";
  ExpectInputError(LogTool("survey --world " + bad + args), "\"segments\"", {log, truth});
  ExpectInputError(LogTool("survey --world " + TempPath("missing.json") + args), "cannot open", {log, truth});
}

TEST(LogToolBadInput, MalformedStationsCsv) {
  const Inputs in = Generate();
  const std::string log = TempPath("o.lcm"), truth = TempPath("t.csv");
  const std::string bad = TempPath("bad.csv");
  const std::string args = " --world " + in.world + " --stations " + bad + " --out " + log + " --truth-out " + truth;
  std::ofstream(bad) << "x,y,theta\n1,2,0\n3,four,0\n";
  ExpectInputError(LogTool("survey" + args), "bad.csv:3: 'four' is not a number", {log, truth});
  std::ofstream(bad) << "x,y\n1,2\n";
  ExpectInputError(LogTool("survey" + args), "header", {log, truth});
  std::ofstream(bad) << "x,y,theta\n1,2\n";
  ExpectInputError(LogTool("survey" + args), "2 fields, expected 3", {log, truth});
  std::ofstream(bad) << "x,y,theta,world\n1,2,0,1\n";  // only one --world
  ExpectInputError(LogTool("survey" + args), "uses world 1 but only 1 world(s)", {log, truth});
  std::ofstream(bad) << "x,y,theta\n";
  ExpectInputError(LogTool("survey" + args), "no stations", {log, truth});
}

TEST(LogToolBadInput, BadFlags) {
  const Inputs in = Generate();
  const std::string log = TempPath("o.lcm"), truth = TempPath("t.csv");
  const std::string base = "survey --world " + in.world + " --stations " + in.stations + " --truth-out " + truth;
  ExpectInputError(LogTool(base + " --out " + log + " --pose-noise 0.3,0.3"), "has 2 values, expected 3", {log, truth});
  ExpectInputError(LogTool(base + " --out " + log + " --pose-noise 0.3,0.3,3dog"), "not a finite number", {log, truth});
  ExpectInputError(LogTool(base + " --out " + log + " --pose-noise 0.3,-0.3,3deg"), "must be >= 0", {log, truth});
  ExpectInputError(LogTool(base + " --out " + log + " --pose-noise 1,1,1 --drift 0,0,0"), "not both", {log, truth});
  ExpectInputError(LogTool(base + " --out " + log + " --drift 0.1,0.2"), "expected scale,heading_drift_per_m,noise",
                   {log, truth});
  ExpectInputError(LogTool(base + " --out " + log + " --sensor hokuyo"), "is not one of typhoon, cyclone", {log, truth});
  ExpectInputError(LogTool(base + " --out " + log + " --points -5"), "points", {log, truth});
  ExpectInputError(LogTool(base + " --out " + log + " --max-range 1"), "max_range", {log, truth});
  ExpectInputError(LogTool(base + " --out " + log + " --frobnicate 3"), "unknown option --frobnicate", {log, truth});
  ExpectInputError(LogTool(base), "--out is required", {truth});
  ExpectInputError(LogTool("survey --stations " + in.stations + " --out " + log), "--world is required", {log});
  ExpectInputError(LogTool("generate --kind cave --world-out " + log + " --stations-out " + truth),
                   "is not one of", {log, truth});
  ExpectInputError(LogTool("render " + log + " --out " + truth), "cannot open", {log, truth});
  ExpectInputError(LogTool("export"), "expected LOG", {});
  // record fails before touching the bus.
  std::ofstream(TempPath("exists.lcm")) << "x";
  ExpectInputError(LogTool("record --out " + TempPath("exists.lcm")), "refusing to overwrite", {});
  ExpectInputError(LogTool("record --channels '(' --out " + log), "not a valid regex", {log});
  ExpectInputError(LogTool("record"), "--out is required", {});
}

// Issue 11: `info LOG --json-out LOG` replaced the log with its JSON summary, exit 0. No
// subcommand may write over a file it reads, however the path is spelled.
TEST(LogToolBadInput, NoSubcommandOverwritesItsInput) {
  const Inputs in = Generate();
  const std::string log = TempPath("precious.lcm");
  ASSERT_EQ(LogTool("survey --world " + in.world + " --stations " + in.stations + " --points 64 --quiet --out " + log)
                .exit_code,
            0);
  const std::string rel = TempPath("rel.txt"), poses = TempPath("poses.csv");
  std::ofstream(rel) << "1 2 1 0 0 0 0 0\n";
  std::ofstream(poses) << "utime,x,y,theta\n1000000,0,0,0\n2000000,1,0,0\n";
  const std::vector<std::string> inputs = {log, in.world, in.stations, rel, poses};
  std::vector<std::string> before;
  for (const std::string& f : inputs) before.push_back(ReadAll(f));
  // The same file through another spelling of its path.
  const std::string log_again = Dir() + "/./" + std::filesystem::path(log).filename().string();
  const std::string survey = "survey --world " + in.world + " --stations " + in.stations + " --points 64 --quiet";
  const std::vector<std::string> commands = {
      "info " + log + " --json-out " + log,
      "info " + log + " --json-out " + log_again,
      "info --json " + log + " --json-out " + log,
      "export " + log + " --poses SIM_TRUTH --out " + log,
      "export " + log + " --scans-out " + log_again,
      "render " + log + " --out " + log,
      "render " + log + " --world " + in.world + " --out " + in.world,
      survey + " --out " + in.world,
      survey + " --out " + TempPath("s.lcm") + " --truth-out " + in.stations,
      "import-carmen " + log + " " + log_again,
      "relations --relations " + rel + " --poses " + poses + " --json-out " + poses,
      "relations --relations " + rel + " --poses " + poses + " --errors-out " + rel,
  };
  for (const std::string& command : commands) {
    SCOPED_TRACE(command);
    const RunResult r = LogTool(command);
    ExpectInputError(r, "is an input of this run", {TempPath("s.lcm")});
    EXPECT_TRUE(r.out.empty()) << "nothing may be reported before the refusal: " << r.out;
    for (size_t i = 0; i < inputs.size(); ++i) EXPECT_EQ(ReadAll(inputs[i]), before[i]) << inputs[i] << " changed";
  }
  // A log written as OUT.partial first must not overwrite an input named OUT.partial.
  const std::string partial = TempPath("next.lcm") + ".partial";
  std::ofstream(partial) << before[2];  // a copy of the stations CSV
  const RunResult r =
      LogTool("survey --world " + in.world + " --stations " + partial + " --out " + TempPath("next.lcm"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("OUT.partial"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(FileExists(TempPath("next.lcm")));
  EXPECT_EQ(ReadAll(partial), before[2]);
  std::filesystem::remove(partial);
}

// A log whose LADAR_SCAN message has a wrong fingerprint or a truncated payload.
std::string BadLog(bool truncated) {
  const auto run = logger_test::MakeTestRun(2, 36);
  const std::string path = TempPath(truncated ? "truncated.lcm" : "fingerprint.lcm");
  logger_test::WriteTestLog(path, run);  // a good log ...
  LogWriter w(path);                     // ... overwritten with a bad one
  const auto scan = EncodeMessage(ToLcm(run.scans[0]));
  w.Write("LADAR_SCAN", 1, scan.data(), static_cast<int>(scan.size()));
  TruthReading t;
  t.pose = Pose2(1, 2, 0);
  w.WriteMessage("SIM_TRUTH", 1, ToLcm(t));
  if (truncated) {
    w.Write("LADAR_SCAN", 2, scan.data(), static_cast<int>(scan.size() / 2));
  } else {
    const auto odo = EncodeMessage(ToLcm(OdometryReading{}));
    w.Write("LADAR_SCAN", 2, odo.data(), static_cast<int>(odo.size()));
  }
  w.Close();
  return path;
}

TEST(LogToolBadInput, WrongFingerprintInALog) {
  const std::string log = BadLog(false);
  const std::string csv = TempPath("o.csv"), svg = TempPath("o.svg");
  const RunResult info = LogTool("info " + log);
  EXPECT_EQ(info.exit_code, 2);
  EXPECT_NE(info.out.find("decode errors: 1 on LADAR_SCAN"), std::string::npos) << info.out;
  EXPECT_NE(info.err.find("is not minenav.ladar_scan_t's"), std::string::npos) << info.err;
  EXPECT_EQ(std::count(info.err.begin(), info.err.end(), '\n'), 1);
  ExpectInputError(LogTool("export " + log + " --scans-out " + csv), "it is minenav.odometry_t", {csv});
  ExpectInputError(LogTool("export " + log + " --poses SIM_TRUTH --out " + csv), "channel LADAR_SCAN", {csv});
  ExpectInputError(LogTool("render " + log + " --out " + svg), "is not minenav.ladar_scan_t's", {svg});
}

TEST(LogToolBadInput, TruncatedPayloadInALog) {
  const std::string log = BadLog(true);
  const std::string csv = TempPath("o.csv"), svg = TempPath("o.svg");
  const RunResult info = LogTool("info " + log);
  EXPECT_EQ(info.exit_code, 2);
  EXPECT_NE(info.err.find("truncated or malformed minenav.ladar_scan_t payload"), std::string::npos) << info.err;
  ExpectInputError(LogTool("export " + log + " --scans-out " + csv), "truncated", {csv});
  ExpectInputError(LogTool("render " + log + " --out " + svg), "truncated", {svg});
}

TEST(LogToolBadInput, TruncatedFile) {
  const std::string log = TempPath("cut.lcm");
  logger_test::WriteTestLog(log, logger_test::MakeTestRun(3, 36));
  std::filesystem::resize_file(log, std::filesystem::file_size(log) - 3);
  const std::string csv = TempPath("o.csv");
  const RunResult info = LogTool("info " + log);
  EXPECT_EQ(info.exit_code, 2);
  EXPECT_NE(info.out.find("FILE DAMAGED"), std::string::npos);
  ExpectInputError(LogTool("export " + log + " --poses SIM_TRUTH --out " + csv), "truncated event", {csv});
  const std::string text = TempPath("notes.txt");
  std::ofstream(text) << "this is not an LCM log, just text\n";
  const RunResult not_log = LogTool("info " + text);
  EXPECT_EQ(not_log.exit_code, 2);
  EXPECT_NE(not_log.err.find("bad magic"), std::string::npos) << not_log.err;
}

}  // namespace
}  // namespace minenav
