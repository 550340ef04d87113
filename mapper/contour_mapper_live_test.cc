// The live contour_mapper on a real LCM bus, inside a private network namespace (run
// through tests/bus/private_net.sh, which sets MINENAV_IN_PRIVATE_NET and LCM_DEFAULT_URL
// with a port of its own):
//   * a survey log replayed with lcm-logplayer through the live process gives the map and
//     poses of `contour_mapper --log` on the same log;
//   * stopped (SIGTERM) after half the log and restarted with its checkpoint, it ends with
//     the map and poses of an uninterrupted run;
//   * bad scans are refused with a reason on POSE (converged = false) and in the log, the
//     map is not republished for them, and the process goes on.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <thread>

#include "common/angle.h"
#include "common/file_io.h"
#include "common/node/bus.h"
#include "common/node/contour_map_conversions.h"
#include "common/node/conversions.h"
#include "common/node/event_log.h"
#include "common/node/lcm_bus.h"
#include "mapper/contour_map_io.h"
#include "mapper/test_world.h"
#include "minenav/contour_map_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "tests/child_process.h"
#include "tests/temp_dir.h"
#include "tests/bus/private_bus_test.h"

namespace minenav {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using testing::ChildProcess;
using testing::ReadTextFile;

constexpr int kStations = 8;

int RunChild(const std::vector<std::string>& argv, const std::string& output) {
  ChildProcess p(argv, output);
  const auto code = p.Wait(600.0);
  return code ? *code : -1;
}

// What the test hears on the bus.
class Listener {
 public:
  explicit Listener(const std::string& url) : bus_(url, 1000) {
    Subscribe<pose_estimate_t>(bus_, "POSE", [this](const pose_estimate_t& m) { poses.push_back(m); });
    // Each map once: an unchanged map sent again (--map-republish-period, for processes that
    // start late) is counted apart.
    Subscribe<contour_map_t>(bus_, "CONTOUR_MAP", [this](const contour_map_t& m) {
      if (!maps.empty() && m.version == maps.back().version && m.utime == maps.back().utime)
        ++map_repeats;
      else
        maps.push_back(m);
    });
    Subscribe<heartbeat_t>(bus_, "HEARTBEAT", [this](const heartbeat_t& m) {
      if (m.process == "contour_mapper") heartbeat_pids.push_back(m.pid);
    });
  }
  // Handles messages until pred() holds or timeout_s passes; returns pred().
  template <typename Pred>
  bool SpinUntil(Pred pred, double timeout_s) {
    const auto end = Clock::now() + std::chrono::duration<double>(timeout_s);
    while (!pred() && Clock::now() < end) bus_.HandleFor(50'000);
    return pred();
  }
  LcmBus& bus() { return bus_; }

  std::vector<pose_estimate_t> poses;
  std::vector<contour_map_t> maps;
  int map_repeats = 0;
  std::vector<int> heartbeat_pids;

 private:
  LcmBus bus_;
};

class ContourMapperLiveTest : public testing::PrivateBusTest {
 protected:
  // A survey log of the first kStations stations of the synthetic mine.
  void MakeSurvey() {
    ASSERT_EQ(RunChild({MINENAV_LOG_TOOL_BIN, "generate", "--kind", "mine", "--seed", "2", "--world-out", dir_ / "mine.json",
                   "--stations-out", dir_ / "st.csv"},
                  dir_ / "gen.txt"),
              0)
        << ReadTextFile(dir_ / "gen.txt");
    auto stations = LoadStationsCsv(dir_ / "st.csv");
    ASSERT_GE(stations.size(), static_cast<size_t>(kStations));
    stations.resize(kStations);
    SaveStationsCsv(dir_ / "st.csv", stations);
    ASSERT_EQ(RunChild({MINENAV_LOG_TOOL_BIN, "survey", "--world", dir_ / "mine.json", "--stations", dir_ / "st.csv",
                   "--sensor", "typhoon", "--points", "1024", "--pose-noise", "0.2,0.2,2deg", "--seed", "5", "--out",
                   dir_ / "survey.lcm", "--truth-out", dir_ / "truth.csv"},
                  dir_ / "survey.txt"),
              0)
        << ReadTextFile(dir_ / "survey.txt");
  }

  // The reference: batch mode on the same log.
  void RunBatch() {
    ASSERT_EQ(RunChild({MINENAV_CONTOUR_MAPPER_BIN, "--log", dir_ / "survey.lcm", "--map-out", dir_ / "batch_map.json",
                   "--poses-out", dir_ / "batch_poses.csv"},
                  dir_ / "batch.txt"),
              0)
        << ReadTextFile(dir_ / "batch.txt");
  }

  // Starts the live process and waits until it is on the bus.
  std::unique_ptr<ChildProcess> StartLive(Listener& listener, const std::vector<std::string>& extra,
                                          const std::string& output) {
    std::vector<std::string> argv = {MINENAV_CONTOUR_MAPPER_BIN, "--heartbeat-period", "0.2"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    auto p = std::make_unique<ChildProcess>(argv, output);
    // Its own heartbeat (a stopped predecessor's last one may still be queued).
    const int pid = p->pid();
    const bool heard = listener.SpinUntil(
        [&] {
          return !p->Running() || std::find(listener.heartbeat_pids.begin(), listener.heartbeat_pids.end(), pid) !=
                                      listener.heartbeat_pids.end();
        },
        60.0);
    EXPECT_TRUE(heard && p->Running()) << "no HEARTBEAT from contour_mapper: " << ReadTextFile(output);
    return p;
  }

  // Plays a log with lcm-logplayer (4x real time: the survey's scans are 1 s apart) and
  // waits for one POSE per scan in it.
  void Play(Listener& listener, const std::string& log, size_t expected_poses) {
    ChildProcess player({"lcm-logplayer", "--speed=4", log}, dir_ / "player.txt");
    ASSERT_TRUE(listener.SpinUntil([&] { return listener.poses.size() >= expected_poses; }, 120.0))
        << "heard " << listener.poses.size() << " of " << expected_poses << " POSE messages (lost on UDP?) "
        << ReadTextFile(dir_ / "player.txt");
    const auto code = player.Wait(30.0);
    ASSERT_TRUE(code && *code == 0) << ReadTextFile(dir_ / "player.txt");
    // The CONTOUR_MAP of the last scan follows its POSE.
    listener.SpinUntil([] { return false; }, 0.5);
  }

  static void Stop(ChildProcess& p, const std::string& output) {
    p.Signal(SIGTERM);
    const auto code = p.Wait(300.0);
    ASSERT_TRUE(code.has_value()) << "contour_mapper did not stop: " << ReadTextFile(output);
    EXPECT_EQ(*code, 0) << ReadTextFile(output);
  }

  // Same number of poses with the same utimes, each within 1 mm and 0.001 rad; maps with the
  // same number of contours and vertices, each vertex within 1 mm. Both runs compute the
  // same sequence of doubles (same scans, same odometry, same order); the tolerance only
  // admits a different summation order after a checkpoint rebuilt the segment grid.
  static void ExpectSameResult(const std::string& poses_a, const std::string& map_a, const std::string& poses_b,
                               const std::string& map_b) {
    const auto a = LoadPosesCsv(poses_a), b = LoadPosesCsv(poses_b);
    ASSERT_EQ(a.size(), b.size());
    ASSERT_EQ(a.size(), static_cast<size_t>(kStations));
    for (size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].utime, b[i].utime);
      EXPECT_LT(TranslationDistance(a[i].pose, b[i].pose), 1e-3) << i;
      EXPECT_LT(HeadingDistance(a[i].pose, b[i].pose), 1e-3) << i;
    }
    const auto ma = mapper::LoadContourMapJson(map_a), mb = mapper::LoadContourMapJson(map_b);
    ASSERT_EQ(ma.NumContours(), mb.NumContours());
    auto ia = ma.contours().begin();
    for (auto ib = mb.contours().begin(); ib != mb.contours().end(); ++ia, ++ib) {
      ASSERT_EQ(ia->second.points.size(), ib->second.points.size());
      for (size_t k = 0; k < ia->second.points.size(); ++k)
        EXPECT_LT((ia->second.points[k] - ib->second.points[k]).norm(), 1e-3);
    }
  }

  testing::TempDir dir_{"minenav_contour_mapper_live"};
};

TEST_F(ContourMapperLiveTest, ReplayThroughTheLiveProcessGivesTheBatchMap) {
  ASSERT_NO_FATAL_FAILURE(MakeSurvey());
  ASSERT_NO_FATAL_FAILURE(RunBatch());
  Listener listener(url_);
  const std::string out = dir_ / "live.txt";
  auto live = StartLive(listener, {"--map-out", dir_ / "live_map.json", "--poses-out", dir_ / "live_poses.csv"}, out);
  ASSERT_TRUE(live->Running()) << ReadTextFile(out);
  ASSERT_NO_FATAL_FAILURE(Play(listener, dir_ / "survey.lcm", kStations));
  Stop(*live, out);
  ExpectSameResult(dir_ / "batch_poses.csv", dir_ / "batch_map.json", dir_ / "live_poses.csv", dir_ / "live_map.json");
  // Every scan was mapped; CONTOUR_MAP came with increasing versions and decodes.
  for (const auto& p : listener.poses) EXPECT_TRUE(p.converged) << p.status;
  ASSERT_GE(listener.maps.size(), static_cast<size_t>(kStations));
  for (size_t i = 1; i < listener.maps.size(); ++i) EXPECT_GT(listener.maps[i].version, listener.maps[i - 1].version);
  const ContourMapMessage last = ContourMapFromLcm(listener.maps.back());
  EXPECT_EQ(static_cast<int>(last.contours.size()), mapper::LoadContourMapJson(dir_ / "live_map.json").NumContours());
  EXPECT_EQ(last.num_scans, kStations);
}

TEST_F(ContourMapperLiveTest, RestartFromTheCheckpointEndsLikeAnUninterruptedRun) {
  ASSERT_NO_FATAL_FAILURE(MakeSurvey());
  ASSERT_NO_FATAL_FAILURE(RunBatch());
  // The two halves of the log, split between stations.
  {
    LogReader reader(dir_ / "survey.lcm");
    LogWriter first(dir_ / "first.lcm"), second(dir_ / "second.lcm");
    int scans = 0;
    while (auto e = reader.Next()) {
      LogWriter& w = scans < kStations / 2 ? first : second;
      w.Write(e->channel, e->timestamp, e->data.data(), static_cast<int>(e->data.size()));
      if (e->channel == "LADAR_SCAN") ++scans;
    }
    first.Close();
    second.Close();
  }
  Listener listener(url_);
  const std::vector<std::string> flags = {"--checkpoint", dir_ / "run.ckpt", "--map-out", dir_ / "live_map.json",
                                          "--poses-out", dir_ / "live_poses.csv"};
  {
    const std::string out = dir_ / "live1.txt";
    auto live = StartLive(listener, flags, out);
    ASSERT_TRUE(live->Running()) << ReadTextFile(out);
    ASSERT_NO_FATAL_FAILURE(Play(listener, dir_ / "first.lcm", kStations / 2));
    Stop(*live, out);
    ASSERT_TRUE(fs::exists(dir_ / "run.ckpt")) << ReadTextFile(out);
  }
  {
    const std::string out = dir_ / "live2.txt";
    auto live = StartLive(listener, flags, out);
    ASSERT_TRUE(live->Running()) << ReadTextFile(out);
    EXPECT_NE(ReadTextFile(out).find("resumed from"), std::string::npos) << ReadTextFile(out);
    ASSERT_NO_FATAL_FAILURE(Play(listener, dir_ / "second.lcm", kStations));
    Stop(*live, out);
  }
  ExpectSameResult(dir_ / "batch_poses.csv", dir_ / "batch_map.json", dir_ / "live_poses.csv", dir_ / "live_map.json");
}

// Scans made in a small room and published by the test with their odometry, one at a time.
TEST_F(ContourMapperLiveTest, BadScansAreRefusedOnTheBusAndTheProcessGoesOn) {
  using mapper::testing::MakeScan;
  using mapper::testing::SmallRoomWorld;
  Listener listener(url_);
  const std::string out = dir_ / "live.txt";
  auto live = StartLive(listener, {"--save-map", dir_ / "map.json", "--final-refinement-rounds", "0"}, out);
  ASSERT_TRUE(live->Running()) << ReadTextFile(out);
  int64_t utime = 1'000'000;
  // Publishes odometry at the scan's utime, then the scan, and waits for its POSE.
  auto send = [&](LadarScan scan, const Pose2& odometry) -> pose_estimate_t {
    utime += 1'000'000;
    scan.utime = utime;
    scan.scan_id = utime / 1'000'000;
    OdometryReading o;
    o.utime = utime;
    o.pose = odometry;
    const size_t before = listener.poses.size();
    Publish(listener.bus(), "ODOMETRY", ToLcm(o));
    Publish(listener.bus(), "LADAR_SCAN", ToLcm(scan));
    EXPECT_TRUE(listener.SpinUntil([&] { return listener.poses.size() > before; }, 120.0)) << ReadTextFile(out);
    return listener.poses.empty() ? pose_estimate_t{} : listener.poses.back();
  };
  mapper::testing::ScanSpec spec;
  spec.range_sigma = 0.02;
  const Pose2 a(3, 9, 0.3), b(9, 9.5, -0.5), c(10, 6, 0);
  ASSERT_TRUE(send(MakeScan(SmallRoomWorld(), a, spec), a).converged);
  ASSERT_TRUE(send(MakeScan(SmallRoomWorld(), b, spec), b).converged);
  ASSERT_TRUE(listener.SpinUntil([&] { return listener.maps.size() >= 2; }, 10.0));
  const size_t maps_before = listener.maps.size();

  // Overlaps nothing: another room, odometry says it is there.
  pose_estimate_t r = send(MakeScan(mapper::testing::Rectangle(100, 100, 104, 103), Pose2(102, 101, 0)), Pose2(102, 101, 0));
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.status.find("overlap"), std::string::npos) << r.status;
  // A wildly wrong initial estimate: odometry 9 m and 120 degrees off.
  r = send(MakeScan(SmallRoomWorld(), c, spec), Pose2(1, 11, 2.1));
  EXPECT_FALSE(r.converged) << r.status;
  // Every reading out of range.
  LadarScan blank = MakeScan(SmallRoomWorld(), c, spec);
  for (float& v : blank.ranges) v = 1000.0f;
  r = send(blank, c);
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.status.find("too few usable points"), std::string::npos) << r.status;
  // A malformed scan (no angular step): refused on the bus and counted as a bad message.
  LadarScan malformed = MakeScan(SmallRoomWorld(), c, spec);
  malformed.angle_step = 0;
  r = send(malformed, c);
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.status.find("invalid scan"), std::string::npos) << r.status;
  // Garbage on the scan channel.
  const char garbage[] = "not a scan";
  listener.bus().Publish("LADAR_SCAN", garbage, sizeof(garbage));
  // None of these changed the map: no CONTOUR_MAP was published for them.
  listener.SpinUntil([] { return false; }, 0.5);
  EXPECT_EQ(listener.maps.size(), maps_before);

  // A scan with a hole in it is fine, and the process goes on mapping.
  LadarScan holey = MakeScan(SmallRoomWorld(), c, spec);
  for (size_t i = 100; i < 250; ++i) holey.ranges[i] = std::nanf("");
  r = send(holey, Pose2(10.2, 5.8, 0.05));
  EXPECT_TRUE(r.converged) << r.status;
  EXPECT_LT(TranslationDistance(FromLcm(r.pose), c), 0.03);
  EXPECT_TRUE(listener.SpinUntil([&] { return listener.maps.size() > maps_before; }, 10.0));
  Stop(*live, out);
  const std::string log = ReadTextFile(out);
  EXPECT_GE(testing::LinesContaining(log, "refused").size(), 3u) << log;
  EXPECT_FALSE(testing::LinesContaining(log, "LADAR_SCAN").empty()) << log;  // the garbage, named by channel
  EXPECT_EQ(static_cast<size_t>(mapper::LoadContourMapJson(dir_ / "map.json").NumContours()),
            ContourMapFromLcm(listener.maps.back()).contours.size());
}

}  // namespace
}  // namespace minenav
