// A world that changes (thesis 4.8), through the processes, without a network:
//   - `log_tool survey` with several --world files and a `world` column: scan k is
//     ray-cast in world k (ranges against the brute-force CastRay of that world), SIM_WORLD
//     is written when each world becomes active, a bad index exits 2 with no output;
//   - vehicle_sim --world A --world B --world-change-at T, in batch over a log of commands,
//     then ladar_driver in batch over vehicle_sim's log: the scans before T are cast in A,
//     those from T on in B, and two scans from the same pose differ exactly where the
//     worlds do.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "common/file_io.h"
#include "common/geometry.h"
#include "common/node/event_log.h"
#include "common/scan.h"
#include "minenav/drive_command_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/vehicle_truth_t.hpp"
#include "sim/changing_world.h"
#include "tests/changing_world_fixtures.h"
#include "tests/child_process.h"
#include "tests/log_contents.h"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

namespace fs = std::filesystem;
using testing::ChildProcess;
using testing::ReadChannel;
using testing::ReadTextFile;

struct Result {
  int code = -1;
  std::string output;
};

Result RunProcess(const std::vector<std::string>& argv, const std::string& output) {
  ChildProcess p(argv, output);
  const auto code = p.Wait(120.0);
  return {code.value_or(-1), ReadTextFile(output)};
}

// The ideal sensor: ranges are the exact ray-cast distances (to float precision).
const std::vector<std::string> kIdealLadar = {"--range-sigma", "0", "--range-resolution", "0",
                                              "--mixed-pixel-probability", "0", "--beam-divergence", "0"};

TEST(ChangingWorldSurvey, EachStationIsCastInItsWorldAndTheLogRecordsEachActivation) {
  testing::TempDir dir("minenav_changing_world_test");
  const std::string a = dir / "closed.json", b = dir / "open.json", stations = dir / "st.csv";
  SaveSegmentsJson(a, testing::DoorClosedRoom());
  SaveSegmentsJson(b, testing::DoorOpenRoomWithBox());
  // Stations 0-1 see world 0, 2-3 world 1, 4 world 0 again.
  std::ofstream(stations) << "x,y,theta,world\n0,0,0,0\n-1,2,0.3,0\n0,0,0,1\n1,-2,-0.4,1\n0.5,0.5,1,0\n";
  const std::string log = dir / "survey.lcm";
  std::vector<std::string> args = {MINENAV_LOG_TOOL_BIN, "survey", "--world", a, "--world", b, "--stations", stations,
                                   "--points", "1024", "--line-map", "first", "--quiet", "--out", log};
  args.insert(args.end(), kIdealLadar.begin(), kIdealLadar.end());
  const Result r = RunProcess(args, dir / "survey.txt");
  ASSERT_EQ(r.code, 0) << r.output;

  const std::vector<std::vector<Segment>> worlds = {testing::DoorClosedRoom(), testing::DoorOpenRoomWithBox()};
  const std::vector<Station> st = LoadStationsCsv(stations);
  const auto scans = ReadChannel<ladar_scan_t>(log, "LADAR_SCAN");
  ASSERT_EQ(scans.size(), st.size());
  int differing = 0;
  for (size_t k = 0; k < scans.size(); ++k) {
    const LadarScan scan = FromLcm(scans[k].msg);
    const auto& own = worlds[static_cast<size_t>(st[k].world)];
    const auto& other = worlds[static_cast<size_t>(1 - st[k].world)];
    double max_error = 0.0;
    for (size_t i = 0; i < scan.ranges.size(); ++i) {
      const double bearing = st[k].pose.theta + scan.Bearing(i);
      const auto hit = CastRay(st[k].pose.translation(), bearing, own, 1e3);
      const auto hit_other = CastRay(st[k].pose.translation(), bearing, other, 1e3);
      ASSERT_TRUE(hit && hit_other);
      ASSERT_TRUE(scan.IsValid(i)) << "station " << k << " reading " << i;
      max_error = std::max(max_error, std::abs(scan.ranges[i] - hit->range));
      if (std::abs(hit->range - hit_other->range) > 0.01) ++differing;
    }
    EXPECT_LT(max_error, 1e-4) << "station " << k;
  }
  EXPECT_GT(differing, 200);  // the door and the box are in view: the check has teeth

  // SIM_WORLD when a world becomes active (stations 0, 2, 4), stamped with that scan's
  // utime, version 1, 2, 3; LINE_MAP (--line-map first) once, the first world.
  const auto sim_world = ReadChannel<line_map_t>(log, "SIM_WORLD");
  ASSERT_EQ(sim_world.size(), 3u);
  const std::vector<size_t> activations = {0, 2, 4};
  for (size_t j = 0; j < 3; ++j) {
    const size_t k = activations[j];
    EXPECT_EQ(sim_world[j].msg.utime, scans[k].msg.utime);
    EXPECT_EQ(sim_world[j].timestamp, scans[k].timestamp);
    EXPECT_EQ(sim_world[j].msg.version, static_cast<int64_t>(j + 1));
    EXPECT_EQ(SegmentsFromLcm(sim_world[j].msg).size(), worlds[static_cast<size_t>(st[k].world)].size());
    const std::string& name = sim_world[j].msg.name;
    EXPECT_EQ(name.rfind("world " + std::to_string(st[k].world) + ": ", 0), 0u) << name;
  }
  const auto line_map = ReadChannel<line_map_t>(log, "LINE_MAP");
  ASSERT_EQ(line_map.size(), 1u);
  EXPECT_EQ(SegmentsFromLcm(line_map[0].msg).size(), worlds[0].size());

  // --line-map each follows SIM_WORLD; the default writes none.
  *std::find(args.begin(), args.end(), "first") = "each";
  ASSERT_EQ(RunProcess(args, dir / "survey.txt").code, 0);
  EXPECT_EQ(ReadChannel<line_map_t>(log, "LINE_MAP").size(), 3u);
}

TEST(ChangingWorldSurvey, AWorldIndexOutOfRangeExitsTwoWithOneLineAndNoOutput) {
  testing::TempDir dir("minenav_changing_world_test");
  const std::string a = dir / "closed.json", b = dir / "open.json", stations = dir / "st.csv";
  SaveSegmentsJson(a, testing::DoorClosedRoom());
  SaveSegmentsJson(b, testing::DoorOpenRoomWithBox());
  std::ofstream(stations) << "x,y,theta,world\n0,0,0,0\n0,0,0,1\n0,0,0,2\n";
  const std::string log = dir / "survey.lcm", truth = dir / "truth.csv";
  const Result r = RunProcess({MINENAV_LOG_TOOL_BIN, "survey", "--world", a, "--world", b, "--stations", stations,
                               "--out",
                        log, "--truth-out", truth},
                       dir / "survey.txt");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.output.find("uses world 2 but only 2 world(s)"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_FALSE(fs::exists(log));
  EXPECT_FALSE(fs::exists(truth));
  std::ofstream(stations) << "x,y,theta,world\n0,0,0,-1\n";
  EXPECT_EQ(
      RunProcess({MINENAV_LOG_TOOL_BIN, "survey", "--world", a, "--stations", stations, "--out", log}, dir / "o.txt").code,
      2);
  EXPECT_FALSE(fs::exists(log));
}

TEST(ChangingWorldSurvey, GenerateWritesEveryScenarioReadyForTheSurvey) {
  testing::TempDir dir("minenav_changing_world_test");
  for (const std::string& name : ChangingWorldScenarioNames()) {
    const ChangingWorldScenario sc = ChangingWorldScenarioByName(name);
    const std::string pattern = dir / (name + "_{}.json"), stations = dir / (name + ".csv");
    Result r = RunProcess({MINENAV_LOG_TOOL_BIN, "generate", "--kind", name, "--world-out", pattern, "--stations-out",
                           stations},
                          dir / "gen.txt");
    ASSERT_EQ(r.code, 0) << r.output;
    std::vector<std::string> survey = {MINENAV_LOG_TOOL_BIN, "survey", "--stations", stations, "--points", "256",
                                       "--quiet", "--out", dir / (name + ".lcm")};
    for (size_t k = 0; k < sc.worlds.size(); ++k) {
      const std::string path = dir / (name + "_" + std::to_string(k) + ".json");
      const std::vector<Segment> world = LoadSegmentsJson(path);
      ASSERT_EQ(world.size(), sc.worlds[k].size()) << path;
      for (size_t i = 0; i < world.size(); ++i) {  // the JSON file keeps about 10 digits
        EXPECT_NEAR((world[i].a - sc.worlds[k][i].a).norm(), 0.0, 1e-7) << path << " segment " << i;
        EXPECT_NEAR((world[i].b - sc.worlds[k][i].b).norm(), 0.0, 1e-7) << path << " segment " << i;
      }
      survey.insert(survey.end(), {"--world", path});
      EXPECT_NE(r.output.find("--world " + path), std::string::npos) << "prints the survey command: " << r.output;
    }
    const std::vector<Station> st = LoadStationsCsv(stations);
    ASSERT_EQ(st.size(), sc.stations.size());
    int activations = 0;
    for (size_t k = 0; k < st.size(); ++k) {
      EXPECT_EQ(st[k].world, sc.stations[k].world);
      EXPECT_NEAR(st[k].pose.x, sc.stations[k].pose.x, 1e-9);
      EXPECT_NEAR(st[k].pose.theta, sc.stations[k].pose.theta, 1e-9);
      activations += k == 0 || st[k].world != st[k - 1].world ? 1 : 0;
    }
    r = RunProcess(survey, dir / "survey.txt");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(ReadChannel<line_map_t>(dir / (name + ".lcm"), "SIM_WORLD").size(), static_cast<size_t>(activations))
        << name;
    EXPECT_EQ(ReadChannel<ladar_scan_t>(dir / (name + ".lcm"), "LADAR_SCAN").size(), st.size()) << name;
  }
  // Several worlds need '{}' in --world-out: exit 2, one line, nothing written.
  const Result r = RunProcess({MINENAV_LOG_TOOL_BIN, "generate", "--kind", "doors_open", "--world-out",
                               dir / "w.json", "--stations-out", dir / "s.csv"},
                              dir / "gen.txt");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.output.find("needs '{}'"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_FALSE(fs::exists(dir / "w.json"));
  EXPECT_FALSE(fs::exists(dir / "s.csv"));
}

constexpr int64_t kT0 = 1'700'000'000'000'000;

// STOP commands every 0.5 s for `seconds`: the vehicle stands still; the log gives the clock.
std::string WriteStopLog(const std::string& path, double seconds) {
  LogWriter w(path);
  for (int64_t k = 0; k * 500'000 <= std::llround(seconds * 1e6); ++k) {
    drive_command_t c{};
    c.utime = kT0 + k * 500'000;
    c.seq = k;
    c.mode = drive_command_t::STOP;
    c.timeout = 0.5;
    w.Write("DRIVE_COMMAND", c);
  }
  w.Close();
  return path;
}

TEST(ChangingWorldProcesses, VehicleSimChangesTheWorldOnTimeAndTheLadarCastsTheNewOne) {
  testing::TempDir dir("minenav_changing_world_test");
  const std::string a = dir / "closed.json", b = dir / "open.json";
  SaveSegmentsJson(a, testing::DoorClosedRoom());
  SaveSegmentsJson(b, testing::DoorOpenRoomWithBox());
  const std::string commands = WriteStopLog(dir / "commands.lcm", 4.0);
  const std::string sim_log = dir / "sim.lcm", scan_log = dir / "scans.lcm";
  Result r = RunProcess({MINENAV_VEHICLE_SIM_BIN, "--log", commands, "--log-out", sim_log, "--world", a, "--world", b,
                  "--world-change-at", "2", "--start-pose", "0,0,0", "--rate", "20", "--map-period", "1"},
                 dir / "sim.txt");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("world changed at 2 s"), std::string::npos) << r.output;

  // SIM_WORLD: the first world at t0 and t0 + 1 s, the second at once at t0 + 2 s (before
  // that tick's truth sample) and then every period. LINE_MAP stays the first world.
  const auto worlds = ReadChannel<line_map_t>(sim_log, "SIM_WORLD");
  ASSERT_GE(worlds.size(), 5u);
  int64_t change_utime = -1;
  int64_t last_version = -1;
  for (const auto& w : worlds) {
    const size_t n = SegmentsFromLcm(w.msg).size();
    const bool after = w.msg.utime >= kT0 + 2'000'000;
    EXPECT_EQ(n, after ? testing::DoorOpenRoomWithBox().size() : testing::DoorClosedRoom().size()) << w.msg.utime;
    EXPECT_EQ(w.msg.name, after ? b : a);
    EXPECT_GE(w.msg.version, last_version);
    if (after && change_utime < 0) {
      change_utime = w.msg.utime;
      EXPECT_GT(w.msg.version, last_version);
    }
    last_version = w.msg.version;
  }
  EXPECT_EQ(change_utime, kT0 + 2'000'000);
  for (const auto& m : ReadChannel<line_map_t>(sim_log, "LINE_MAP"))
    EXPECT_EQ(SegmentsFromLcm(m.msg).size(), testing::DoorClosedRoom().size());

  std::vector<std::string> ladar = {MINENAV_LADAR_DRIVER_BIN, "--log",    sim_log, "--log-out",
                                    scan_log,                 "--points", "1024"};
  ladar.insert(ladar.end(), kIdealLadar.begin(), kIdealLadar.end());
  r = RunProcess(ladar, dir / "ladar.txt");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto scans = ReadChannel<ladar_scan_t>(scan_log, "LADAR_SCAN");
  ASSERT_EQ(scans.size(), 41u);  // 10 Hz over [0, 4] s
  const testing::WorldMatch match = testing::MatchScans(scans, Pose2(), testing::DoorClosedRoom(),
                                                        testing::DoorOpenRoomWithBox(), 1e-4);
  for (size_t k = 0; k < scans.size(); ++k) {
    const bool after = scans[k].msg.utime >= kT0 + 2'000'000;
    EXPECT_EQ(match.world[k], after ? 1 : 0) << "scan " << k << " at " << scans[k].msg.utime - kT0 << " us";
  }
  // Same pose, before and after: the scans differ exactly at the readings where the
  // worlds' ray casts differ.
  EXPECT_EQ(testing::DifferingReadings(scans[5].msg, scans[35].msg, 1e-3),
            testing::DifferingRayCasts(scans[5].msg, Pose2(), testing::DoorClosedRoom(),
                                       testing::DoorOpenRoomWithBox(), 1e-3));
  EXPECT_GT(testing::DifferingReadings(scans[5].msg, scans[35].msg, 1e-3).size(), 100u);
}

TEST(ChangingWorldProcesses, VehicleSimRejectsBadChangeTimes) {
  testing::TempDir dir("minenav_changing_world_test");
  const std::string a = dir / "closed.json", b = dir / "open.json";
  SaveSegmentsJson(a, testing::DoorClosedRoom());
  SaveSegmentsJson(b, testing::DoorOpenRoomWithBox());
  const std::string commands = WriteStopLog(dir / "commands.lcm", 1.0);
  const std::vector<std::string> base = {MINENAV_VEHICLE_SIM_BIN, "--log", commands, "--world", a};
  struct Case {
    std::vector<std::string> extra;
    std::string needle;
  };
  const std::vector<Case> cases = {
      {{"--world", b}, "need --world-change-at with 1 time"},
      {{"--world", b, "--world-change-at", "1,2"}, "has 2 time(s), expected 1"},
      {{"--world", b, "--world", a, "--world-change-at", "3,2"}, "times must increase"},
      {{"--world", b, "--world-change-at", "0"}, "times must be in (0, 1e7] s"},
      {{"--world", b, "--world-change-at", "soon"}, "--world-change-at"},
      {{"--world-change-at", "2"}, "needs more than one --world"},
      {{"--world", dir / "missing.json", "--world-change-at", "2"}, "missing.json"},
      {{"--world"}, "--world needs a file"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> argv = base;
    argv.insert(argv.end(), c.extra.begin(), c.extra.end());
    const Result r = RunProcess(argv, dir / "o.txt");
    EXPECT_EQ(r.code, 2) << c.needle << ": " << r.output;
    EXPECT_NE(r.output.find(c.needle), std::string::npos) << r.output;
    EXPECT_EQ(testing::LinesContaining(r.output, "error").size(), 1u) << r.output;
  }
}

}  // namespace
}  // namespace minenav
