// The sump-shear cycle live on the LCM bus inside a private network namespace
// (tests/bus/private_net.sh, port 7820): vehicle_sim (with its cutterhead) + ladar_driver +
// contour_mapper (live; its POSE is the cutter's only pose) + cutter. The test asks for a
// 0.6 m box cut on CUT_TASK with no face given (the cutter finds it in CONTOUR_MAP) and
// judges the end: TASK_STATUS DONE; the face in the true world (the last SIM_WORLD) and, in
// the normal build, in the live contour map (the last CONTOUR_MAP) within 5 cm of 0.6 m across
// the drum; the face outside the drum's width where it was. Scans of 512 points every 2 s keep the live mapper
// up with them on a loaded machine. Faster appendages than the defaults (shear 4 s,
// boom 1 m/s, sump 0.04 m/s in 0.3 m steps) keep the run near a minute.

#include <gtest/gtest.h>

#include <cmath>

#include <chrono>
#include <csignal>
#include <iostream>

#include "common/file_io.h"
#include "common/geometry.h"
#include "common/node/bus.h"
#include "common/node/contour_map_conversions.h"
#include "common/node/conversions.h"
#include "common/node/lcm_bus.h"
#include "common/node/map_updates.h"
#include "minenav/contour_map_t.hpp"
#include "minenav/cutter_command_t.hpp"
#include "minenav/cutter_state_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "minenav/task_status_t.hpp"
#include "tests/bus/private_bus_test.h"
#include "tests/child_process.h"
#include "tests/sanitizer.h"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

using testing::ChildProcess;
using testing::ReadTextFile;

constexpr double kFaceX = 16.0;

std::vector<Segment> Rect(double x0, double y0, double x1, double y1) {
  return {Segment(x0, y0, x1, y0), Segment(x1, y0, x1, y1), Segment(x1, y1, x0, y1), Segment(x0, y1, x0, y0)};
}

// x of the first wall hit from (4, y) along +x.
double FaceX(const std::vector<Segment>& walls, double y) {
  const auto hit = CastRay(Eigen::Vector2d(4.0, y), 0.0, walls, 100.0);
  return hit ? 4.0 + hit->range : -1.0;
}

using CutterBusTest = testing::PrivateBusTest;

TEST_F(CutterBusTest, ABoxCutEndsWithinFiveCentimetresInTheWorldAndInTheLiveMap) {
  testing::TempDir dir("minenav_cutter_bus");
  std::vector<Segment> world = Rect(-8, -3, kFaceX, 3);
  for (const Segment& s : Rect(2, 2.0, 2.6, 2.6)) world.push_back(s);  // a crib block by the left rib
  const std::string world_file = dir / "entry.json";
  SaveSegmentsJson(world_file, world);
  const double depth = 0.6;

  LcmBus bus(url_.c_str(), 10000);
  std::vector<task_status_t> status;
  std::optional<line_map_t> sim_world;
  std::optional<contour_map_t> map;
  int poses = 0, unconverged = 0;
  double max_latency = 0.0;  // s from a scan to its POSE
  const auto wall_us = [] {
    return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
        .count();
  };
  Subscribe<task_status_t>(bus, "TASK_STATUS", [&](const task_status_t& m) { status.push_back(m); });
  Subscribe<line_map_t>(bus, "SIM_WORLD", [&](const line_map_t& m) { sim_world = m; });
  Subscribe<contour_map_t>(bus, "CONTOUR_MAP", [&](const contour_map_t& m) { map = m; });
  Subscribe<pose_estimate_t>(bus, "POSE", [&](const pose_estimate_t& m) {
    poses += m.converged ? 1 : 0;
    unconverged += m.converged ? 0 : 1;
    max_latency = std::max(max_latency, static_cast<double>(wall_us() - m.utime) * 1e-6);
  });

  // Every scan inserted (the default policy), each insert refitted with the 20 nearest scans
  // within 15 m (fleet/mission.fleet). Under ASan the contour fit's arithmetic runs 15-19 times
  // slower (the integral error alone: 19x), an insert with 20 scans took 6 s against the
  // scans' 2 s and the cut stopped on a stale pose: the 5 nearest there.
  const char* fit_scans = testing::kUnderAddressSanitizer ? "5" : "20";
  ChildProcess mapper({MINENAV_CONTOUR_MAPPER_BIN, "--run-for", "230", "--final-refinement-rounds", "0",
                       "--mapper.fit-scans", fit_scans, "--mapper.local-fit-radius", "15"},
                      dir / "mapper.txt");
  ChildProcess ladar({MINENAV_LADAR_DRIVER_BIN, "--run-for", "230", "--scan-rate", "0.5", "--points", "512", "--seed",
                      "4", "--mixed-pixel-probability", "0"},
                     dir / "ladar.txt");
  // 0.5 m from the face, 2 degrees off square.
  ChildProcess sim({MINENAV_VEHICLE_SIM_BIN, "--run-for", "230", "--world", world_file, "--start-pose",
                    "10.5,0.1,2deg", "--cutterhead.shear-time", "4", "--cutterhead.boom-rate", "1"},
                   dir / "sim.txt");
  // The pose may be several seconds old on a loaded 2-core machine (a scan every 2 s, poses
  // every few seconds as in 6.4.2, and the mapper's lag behind them while other builds run:
  // up to 10 s seen with 1 Hz scans at a load of 7): 10 s here; the stop itself is cutter_sim_test's.
  ChildProcess cutter({MINENAV_CUTTER_BIN, "--run-for", "230", "--cutter.sump-speed", "0.04", "--cutter.sump-step",
                       "0.3", "--cutter.cusp-speed", "0.05", "--cutter.approach-speed", "0.07",
                       "--cutter.max-pose-age", "10"},
                      dir / "cutter.txt");
  const auto logs = [&] {
    return "\nmapper: " + ReadTextFile(dir / "mapper.txt") + "\nladar: " + ReadTextFile(dir / "ladar.txt") +
           "\nsim: " + ReadTextFile(dir / "sim.txt") + "\ncutter: " + ReadTextFile(dir / "cutter.txt");
  };
  // The cutter needs a pose and a map with the face in it.
  ASSERT_TRUE(Pump(bus, 40.0, [&] { return poses >= 3 && map.has_value(); })) << poses << " poses" << logs();
  Pump(bus, 1.5);
  cutter_command_t task{};
  task.seq = 11;
  task.action = cutter_command_t::SUMP;
  task.sump_depth = depth;
  // Once, then again while no TASK_STATUS answers (UDP may lose it).
  for (int k = 0; k < 5 && status.empty(); ++k) {
    task.utime = wall_us();
    Publish(bus, "CUT_TASK", task);
    Pump(bus, 2.0, [&] { return !status.empty(); });
  }
  ASSERT_FALSE(status.empty()) << logs();
  ASSERT_NE(status.front().state, task_status_t::FAILED) << status.front().message << logs();
  const auto ended = [&] {
    return !status.empty() &&
           (status.back().state == task_status_t::DONE || status.back().state == task_status_t::FAILED);
  };
  ASSERT_TRUE(Pump(bus, 180.0, ended)) << (status.empty() ? "" : status.back().message) << logs();
  std::cout << poses << " poses (" << unconverged << " unconverged), scan to POSE at most " << max_latency << " s\n";
  EXPECT_EQ(status.back().state, task_status_t::DONE) << status.back().message << logs();
  EXPECT_EQ(status.back().task_id, 11);
  ASSERT_TRUE(sim_world.has_value());
  const std::vector<Segment> truth = SegmentsFromLcm(*sim_world);
  std::cout << status.back().message << "\n";
  for (double y : {-1.2, 0.0, 1.2}) {
    std::cout << "y " << y << ": true depth " << FaceX(truth, y) - kFaceX << " m\n";
    EXPECT_NEAR(FaceX(truth, y) - kFaceX, depth, 0.05) << "true world at y = " << y;
  }
  EXPECT_NEAR(FaceX(truth, -2.5), kFaceX, 1e-6);
  // The cut in the live map is an accuracy requirement of the normal build. Under the
  // sanitizers the contour fit runs 15-19 times slower: with another test beside it on the 2
  // cores the map still showed the first cycle's face (0.36 of 0.60 m at one line) 60 s after
  // DONE (2026-12-03), while alone it passed. What runs there is the cut on the bus, its true
  // depth and every process's clean exit.
  if (testing::kUnderAddressSanitizer) {
    std::cout << "the live map's depth is judged in the normal build only (not under the sanitizers)\n";
  } else {
    // Scans of the finished cut into the map: the 4.8 editing removes a face seen through over a
    // few scans (the first cycle's face lingered at 0.3 m two seconds after DONE). On a loaded
    // machine the mapper may take longer (a scan every 2 s, each edit needs the face seen
    // through again): the map is given up to 60 s after DONE to show the cut, then judged.
    const int64_t done_at = status.back().utime;
    ASSERT_TRUE(Pump(bus, 40.0, [&] { return map && map->utime > done_at + 8'000'000; })) << logs();
    const auto map_shows_cut = [&] {
      const std::vector<Segment> m = ContourMapSegments(ContourMapFromLcm(*map));
      for (double y : {-1.2, 0.0, 1.2})
        if (std::abs(FaceX(m, y) - kFaceX - depth) > 0.05) return false;
      return true;
    };
    Pump(bus, 60.0, map_shows_cut);
    const std::vector<Segment> mapped = ContourMapSegments(ContourMapFromLcm(*map));
    for (double y : {-1.2, 0.0, 1.2}) {
      std::cout << "y " << y << ": in the contour map " << FaceX(mapped, y) - kFaceX << " m\n";
      EXPECT_NEAR(FaceX(mapped, y) - kFaceX, depth, 0.05) << "contour map at y = " << y << logs();
    }
    EXPECT_NEAR(FaceX(mapped, -2.5), kFaceX, 0.05);
  }
  for (ChildProcess* p : {&cutter, &sim, &ladar, &mapper}) p->Signal(SIGTERM);
  EXPECT_EQ(cutter.Wait(10.0), 0) << logs();
  EXPECT_EQ(sim.Wait(10.0), 0) << logs();
  EXPECT_EQ(ladar.Wait(10.0), 0) << logs();
  EXPECT_EQ(mapper.Wait(30.0), 0) << logs();
}

}  // namespace
}  // namespace minenav
