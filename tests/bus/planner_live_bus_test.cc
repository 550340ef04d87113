// Issue 13: the path planner plans on a contour map built live by the mapper from the
// simulated survey. Inside a private network namespace (tests/bus/private_net.sh):
// vehicle_sim + ladar_driver (both on the same generated mine) + contour_mapper + the
// waypoint_driver survey of the first stations; then path_planner live answers a
// PATH_REQUEST between two surveyed stations. The PATH must be feasible, carry the request id
// and be collision-free against the TRUE world's walls (the independent checker).

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <thread>
#include <vector>

#include "common/file_io.h"
#include "common/geometry.h"
#include "common/node/bus.h"
#include "common/node/contour_map_conversions.h"
#include "common/node/conversions.h"
#include "common/node/lcm_bus.h"
#include "minenav/contour_map_t.hpp"
#include "minenav/path_request_t.hpp"
#include "minenav/path_t.hpp"
#include "planner/testing/path_checker.h"
#include "sim/mine_generator.h"
#include "tests/bus/private_bus_test.h"
#include "tests/child_process.h"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

namespace fs = std::filesystem;
using testing::ChildProcess;
using testing::ReadTextFile;
using PlannerLiveBusTest = testing::PrivateBusTest;

std::vector<Eigen::Vector2d> Miner() {
  const double w = 3.3 / 2, l = 10.0 / 2;
  return {{-l, -w}, {l, -w}, {l, w}, {-l, w}};
}

std::string PoseArg(const Pose2& p) {
  return std::to_string(p.x) + "," + std::to_string(p.y) + "," + std::to_string(p.theta);
}

TEST_F(PlannerLiveBusTest, PlansOnTheContourMapTheMapperBuildsLiveFromTheSurvey) {
  const testing::TempDir dir("planner_live_bus");
  MineOptions mine;  // 2 x 3 pillars of 12 m, 6 m entries
  mine.seed = 5;
  const std::vector<Segment> world = GenerateRoomAndPillarMine(mine);
  std::vector<Station> stations = MineSurveyStations(mine, 42);
  stations.resize(4);  // along the first entry
  SaveSegmentsJson(dir / "mine.json", world);
  WriteFileAtomically(dir / "stations.csv", StationsToCsv(stations));

  const std::string run_for = "120";  // s: every process stops by itself if the test dies
  ChildProcess sim({MINENAV_VEHICLE_SIM_BIN, "--run-for", run_for, "--world", dir / "mine.json", "--start-pose",
                    PoseArg(stations[0].pose), "--seed", "5", "--max-forward-speed", "1.0", "--max-acceleration", "1",
                    "--max-deceleration", "2", "--max-turn-in-place-rate", "0.8", "--max-yaw-acceleration", "2"},
                   dir / "sim.txt");
  ChildProcess ladar({MINENAV_LADAR_DRIVER_BIN, "--run-for", run_for, "--world", dir / "mine.json", "--sensor",
                      "typhoon", "--seed", "5"},
                     dir / "ladar.txt");
  ChildProcess mapper({MINENAV_CONTOUR_MAPPER_BIN, "--run-for", run_for, "--insert-min-translation", "1.0",
                       "--insert-min-rotation", "0.3"},
                      dir / "mapper.txt");
  ChildProcess planner({MINENAV_PATH_PLANNER_BIN, "--run-for", run_for, "--deadline", "10"}, dir / "planner.txt");
  std::this_thread::sleep_for(std::chrono::milliseconds(800));  // everyone subscribed
  ChildProcess driver({MINENAV_WAYPOINT_DRIVER_BIN, "--run-for", "80", "--stations", dir / "stations.csv",
                       "--cruise-speed", "1.0", "--turn-rate", "0.8", "--dwell", "0.3"},
                      dir / "driver.txt");

  LcmBus bus(url_, 1000);
  int64_t map_version = -1;
  int map_contours = 0;
  std::vector<path_t> paths;
  Subscribe<contour_map_t>(bus, "CONTOUR_MAP", [&](const contour_map_t& m) {
    const ContourMapMessage map = ContourMapFromLcm(m);
    map_version = map.version;
    map_contours = static_cast<int>(map.contours.size());
  });
  Subscribe<path_t>(bus, "PATH", [&](const path_t& p) { paths.push_back(p); });

  // The survey: the driver exits after the last station.
  ASSERT_TRUE(Pump(bus, 75.0, [&] { return !driver.Running(); }))
      << "the survey did not finish\n" << ReadTextFile(dir / "driver.txt");
  EXPECT_EQ(driver.Wait(1.0), 0) << ReadTextFile(dir / "driver.txt");
  // Let the mapper publish what it made of the last scans.
  const int64_t version_at_end = map_version;
  Pump(bus, 5.0, [&] { return map_version > version_at_end; });
  ASSERT_GT(map_version, 0) << "no CONTOUR_MAP\n" << ReadTextFile(dir / "mapper.txt");
  EXPECT_GT(map_contours, 0);

  // From station 1 to station 3, heading along the entry.
  path_request_t request{};
  request.utime = std::chrono::duration_cast<std::chrono::microseconds>(
                      std::chrono::system_clock::now().time_since_epoch())
                      .count();
  request.request_id = 1313;
  request.start = ToLcm(Pose2(stations[1].pose.x, stations[1].pose.y, 0.0));
  request.goal = ToLcm(Pose2(stations[3].pose.x, stations[3].pose.y, 0.0));
  request.position_tolerance = 0.2;
  request.heading_tolerance = 0.1;
  request.allow_reverse = true;
  request.clearance = 0.15;
  request.allow_unknown = false;
  Publish(bus, "PATH_REQUEST", request);
  ASSERT_TRUE(Pump(bus, 20.0, [&] { return !paths.empty(); })) << "no PATH\n" << ReadTextFile(dir / "planner.txt");

  const path_t& p = paths.front();
  EXPECT_EQ(p.request_id, 1313);
  ASSERT_TRUE(p.feasible) << p.status << "\n" << ReadTextFile(dir / "planner.txt");
  ASSERT_GT(p.num_segments, 0);
  std::vector<testing::CheckedPiece> pieces;
  for (const path_segment_t& s : p.segments) pieces.push_back({s.motion, FromLcm(s.end)});
  EXPECT_NEAR(pieces.back().end.x, stations[3].pose.x, 1e-4);
  EXPECT_NEAR(pieces.back().end.y, stations[3].pose.y, 1e-4);
  testing::PathCheckSettings settings;
  settings.polygon = Miner();
  settings.clearance = 0.05;  // the request kept 0.15 m from the mapped walls; the map is good to a few cm
  settings.sample_step = 0.02;
  const testing::PathCheckReport report = testing::CheckPath(world, FromLcm(p.start), pieces, settings);
  EXPECT_TRUE(report.ok) << report.problem << " (least clearance to the true walls " << report.min_clearance << " m)";

  for (ChildProcess* c : {&planner, &mapper, &ladar, &sim}) c->Signal(SIGTERM);
  EXPECT_EQ(planner.Wait(10.0), 0) << ReadTextFile(dir / "planner.txt");
  for (ChildProcess* c : {&mapper, &ladar, &sim}) c->Wait(20.0);
}

}  // namespace
}  // namespace minenav
