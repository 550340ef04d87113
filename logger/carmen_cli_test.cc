// log_tool import-carmen and log_tool relations as users run them: small inline inputs
// with exact answers and bad input (exit 2, one line, no output).

#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/angle.h"
#include "common/file_io.h"
#include "common/node/conversions.h"
#include "common/node/event_log.h"
#include "logger/log_tool_run.h"
#include "logger/test_logs.h"

namespace minenav {
namespace {

using logger_test::FileExists;
using logger_test::LogTool;
using logger_test::ReadAll;
using logger_test::RunResult;
using logger_test::TempPath;

std::string WriteText(const std::string& name, const std::string& text) {
  const std::string path = TempPath(name);
  std::ofstream(path) << text;
  return path;
}

void ExpectInputError(const RunResult& r, const std::string& needle, const std::string& output) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << "stderr: " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "stderr: " << r.err;
  if (!output.empty()) {
    EXPECT_FALSE(FileExists(output)) << output;
    EXPECT_FALSE(FileExists(output + ".partial")) << output;
  }
}

// Three scans (the third stamped before the second, as in Intel), laser 0.1 m ahead of
// the robot, two ODOM lines in between.
constexpr const char* kClf =
    "# test\n"
    "ODOM 0 0 0 0.5 0 0 10.000000 h 0\n"
    "FLASER 3 1.0 2.0 81.91 0.1 0 0 0 0 0 10.050000 h 0\n"
    "ODOM 0.05 0 0 0.5 0 0 10.100000 h 0\n"
    "FLASER 3 1.0 2.0 3.0 0.2 0 0 0.1 0 0 10.300000 h 0\n"
    "FLASER 3 1.5 2.5 3.5 0.3 0 0 0.2 0 0 10.200000 h 0\n";

struct Event {
  std::string channel;
  int64_t timestamp;
  int64_t utime;
};

std::vector<Event> ReadEvents(const std::string& path, std::vector<LadarScan>* scans,
                              std::vector<OdometryReading>* odometry) {
  LogReader reader(path);
  std::vector<Event> events;
  while (auto e = reader.Next()) {
    std::string error;
    if (e->channel == "LADAR_SCAN") {
      ladar_scan_t m{};
      EXPECT_TRUE(DecodeMessage(e->data.data(), static_cast<int>(e->data.size()), e->channel, &m, &error)) << error;
      scans->push_back(FromLcm(m));
      events.push_back({e->channel, e->timestamp, m.utime});
    } else if (e->channel == "ODOMETRY") {
      odometry_t m{};
      EXPECT_TRUE(DecodeMessage(e->data.data(), static_cast<int>(e->data.size()), e->channel, &m, &error)) << error;
      odometry->push_back(FromLcm(m));
      events.push_back({e->channel, e->timestamp, m.utime});
    } else {
      ADD_FAILURE() << "unexpected channel " << e->channel;
    }
  }
  return events;
}

TEST(CarmenCli, ImportWritesScansAndOdometryInOrder) {
  const std::string in = WriteText("small.clf", kClf);
  const std::string out = TempPath("small.lcm");
  const RunResult r = LogTool("import-carmen " + in + " " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, out + "\n");
  EXPECT_NE(r.err.find("3 scans on LADAR_SCAN, 2 odometry on ODOMETRY"), std::string::npos) << r.err;
  std::vector<LadarScan> scans;
  std::vector<OdometryReading> odo;
  const std::vector<Event> events = ReadEvents(out, &scans, &odo);
  // Merged by time, each stream in file order; odometry first on equal times.
  ASSERT_EQ(events.size(), 5u);
  const std::vector<std::string> channels = {"ODOMETRY", "LADAR_SCAN", "ODOMETRY", "LADAR_SCAN", "LADAR_SCAN"};
  const std::vector<int64_t> utimes = {10000000, 10050000, 10100000, 10300000, 10200000};
  const std::vector<int64_t> stamps = {10000000, 10050000, 10100000, 10300000, 10300000};
  for (size_t i = 0; i < events.size(); ++i) {
    EXPECT_EQ(events[i].channel, channels[i]) << i;
    EXPECT_EQ(events[i].utime, utimes[i]) << i;      // raw ipc time
    EXPECT_EQ(events[i].timestamp, stamps[i]) << i;  // never backwards
  }
  ASSERT_EQ(scans.size(), 3u);
  EXPECT_EQ(scans[2].scan_id, 2);
  EXPECT_NEAR(scans[0].sensor_offset.x, 0.1, 1e-9);
  EXPECT_NEAR(scans[0].start_angle, -kPi / 2, 1e-6);
  EXPECT_TRUE(std::isnan(scans[0].ranges[2]));  // 81.91: no return
  EXPECT_FLOAT_EQ(scans[1].ranges[2], 3.0f);
  ASSERT_EQ(odo.size(), 2u);
  EXPECT_DOUBLE_EQ(odo[1].pose.x, 0.05);
  EXPECT_DOUBLE_EQ(odo[1].v, 0.5);

  // log_tool info reads it cleanly.
  const RunResult info = LogTool("info " + out);
  EXPECT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("minenav.ladar_scan_t"), std::string::npos) << info.out;
}

TEST(CarmenCli, ImportOptions) {
  const std::string in = WriteText("opts.clf", kClf);
  // Laser-line robot poses on ODOMETRY as well (merged by time with the ODOM lines).
  const std::string always = TempPath("always.lcm");
  ASSERT_EQ(LogTool("import-carmen " + in + " " + always + " --scan-odometry always").exit_code, 0);
  std::vector<LadarScan> scans;
  std::vector<OdometryReading> odo;
  ReadEvents(always, &scans, &odo);
  ASSERT_EQ(odo.size(), 5u);
  EXPECT_EQ(odo[1].utime, 10050000);  // the first scan's robot pose
  EXPECT_EQ(odo[4].seq, 4);

  const std::string never = TempPath("never.lcm");
  ASSERT_EQ(LogTool("import-carmen " + in + " " + never + " --scan-odometry never --monotonic-times").exit_code, 0);
  scans.clear();
  odo.clear();
  const std::vector<Event> events = ReadEvents(never, &scans, &odo);
  ASSERT_EQ(scans.size(), 3u);
  EXPECT_EQ(scans[2].utime, 10300001);  // made strictly increasing
  EXPECT_EQ(odo.size(), 2u);
}

TEST(CarmenCli, ImportBadInput) {
  const std::string out = TempPath("bad.lcm");
  ExpectInputError(LogTool("import-carmen /nonexistent/x.clf " + out), "/nonexistent/x.clf: cannot open", out);
  const std::string bad = WriteText("bad.clf", "# x\nFLASER 3 1 2 0 0 0 0 0 0 1.0 h 0\n");
  ExpectInputError(LogTool("import-carmen " + bad + " " + out), "bad.clf:2: FLASER: expected 14 fields", out);
  const std::string empty = WriteText("empty.clf", "ODOM 0 0 0 0 0 0 1.0 h 0\n");
  ExpectInputError(LogTool("import-carmen " + empty + " " + out), "no FLASER or ROBOTLASER1 lines", out);
  const std::string good = WriteText("good.clf", kClf);
  ExpectInputError(LogTool("import-carmen " + good + " " + out + " --scan-odometry sometimes"),
                   "--scan-odometry must be auto, always or never", out);
  ExpectInputError(LogTool("import-carmen " + good), "", "");
}

// Issue 11's probe through the command line: a .gz cut at a flush point gave exit 0 with
// 11 of 50 scans, and a 50 MB field a 52 MB "one-line" error.
TEST(CarmenCli, ImportRefusesTruncatedAndOversizedInput) {
  const std::string out = TempPath("hostile.lcm");
  std::string head, tail;
  for (int k = 0; k < 50; ++k)
    (k < 11 ? head : tail) += "FLASER 3 1 2 3 0 0 0 0 0 0 " + std::to_string(100 + k) + ".5 h 0\n";
  const std::string gz = TempPath("cut.clf.gz");
  gzFile f = gzopen(gz.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  gzwrite(f, head.data(), static_cast<unsigned>(head.size()));
  ASSERT_EQ(gzflush(f, Z_SYNC_FLUSH), Z_OK);
  const auto flush_point = std::filesystem::file_size(gz);
  gzwrite(f, tail.data(), static_cast<unsigned>(tail.size()));
  ASSERT_EQ(gzclose(f), Z_OK);
  const RunResult whole = LogTool("import-carmen " + gz + " " + out);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_NE(whole.err.find("50 scans on LADAR_SCAN"), std::string::npos) << whole.err;
  std::filesystem::remove(out);
  std::filesystem::resize_file(gz, flush_point);
  ExpectInputError(LogTool("import-carmen " + gz + " " + out), gz + ": truncated", out);

  // A 3 MB field: the line is over the 1 MiB limit; the error names the line, and is short.
  const std::string big = WriteText("big.clf", head + "FLASER 3 " + std::string(3'000'000, '7') + " 2 3\n" + tail);
  const RunResult r = LogTool("import-carmen " + big + " " + out);
  ExpectInputError(r, big + ":12: line longer than 1048576 bytes", out);
  EXPECT_LT(r.err.size(), 300u) << r.err.substr(0, 400);
}

// Poses at 1, 2, 3 s; two relations off by known amounts (relations_test.cc's exact case).
TEST(CarmenCli, RelationsExactSmallCase) {
  const std::string rel = WriteText("r.txt", "1 2 1.1 0 0 0 0 " + std::to_string(kPi / 2 + 0.1) +
                                                  "\n2 3 1.0 0.2 0 0 0 -0.05\n");
  const std::string poses = WriteText("p.csv", "utime,x,y,theta\n1000000,0,0,0\n2000000,1,0," +
                                                   std::to_string(kPi / 2) + "\n3000000,1,1," +
                                                   std::to_string(kPi / 2) + "\n");
  const std::string json = TempPath("score.json"), errors = TempPath("errors.csv");
  const RunResult r = LogTool("relations --relations " + rel + " --poses " + poses + " --json-out " + json +
                              " --errors-out " + errors);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("relations 2, scored 2, skipped 0"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("translation (m)              0.1500       0.0707"), std::string::npos) << r.out;
  const nlohmann::json j = nlohmann::json::parse(ReadAll(json));
  EXPECT_EQ(j["n"], 2);
  EXPECT_NEAR(j["translation_m"]["mean"].get<double>(), 0.15, 1e-6);
  EXPECT_NEAR(j["translation_m"]["std"].get<double>(), std::sqrt(2 * 0.05 * 0.05), 1e-6);
  EXPECT_NEAR(j["rotation_deg"]["mean"].get<double>(), (RadToDeg(0.1) + RadToDeg(0.05)) / 2, 1e-4);
  EXPECT_EQ(ReadAll(errors).rfind("t1,t2,translation_m,rotation_deg,odometry_corrected\n1.000000,2.000000,0.100000,", 0),
            0u)
      << ReadAll(errors);

  ExpectInputError(LogTool("relations --poses " + poses), "--relations is required", "");
  ExpectInputError(LogTool("relations --relations " + poses + " --poses " + poses),
                   "expected 8 fields (t1 t2 x y z roll pitch yaw), got 1", "");
  const std::string far = WriteText("far.txt", "100 200 1 0 0 0 0 0\n");
  ExpectInputError(LogTool("relations --relations " + far + " --poses " + poses),
                   "nothing scored: no relation has an estimate within", "");
}

}  // namespace
}  // namespace minenav
