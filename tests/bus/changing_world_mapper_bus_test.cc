// Issue 6, "the live mapper follows a world changed while the fleet runs" (thesis 4.8,
// Figure 23), live on the LCM bus inside a private network namespace
// (tests/bus/private_net.sh): vehicle_sim + ladar_driver + contour_mapper (live), the
// vehicle standing in room A facing the double door of sim/changing_world.h's doors_open
// scenario. The doors open while the fleet runs (vehicle_sim --world-change-at). The
// final CONTOUR_MAP is judged with evaluation/changing_world_judge.h and map_evaluation.h:
//   - before the change the map held the closed doors (the test has teeth);
//   - after it, the door leaves seen through are gone (wall length wrongly kept), the walls
//     seen before and still there are kept (wall length wrongly removed), the walls of the
//     new world seen from the vehicle are covered, and every contour lies on the new world.

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "common/file_io.h"
#include "common/node/bus.h"
#include "common/node/contour_map_conversions.h"
#include "common/node/conversions.h"
#include "common/node/lcm_bus.h"
#include "evaluation/changing_world_judge.h"
#include "evaluation/map_evaluation.h"
#include "minenav/contour_map_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "sim/changing_world.h"
#include "tests/child_process.h"
#include "tests/temp_dir.h"
#include "tests/bus/private_bus_test.h"

namespace minenav {
namespace {

namespace fs = std::filesystem;
using testing::ChildProcess;
using testing::ReadTextFile;

mapper::ContourMap ToContourMap(const contour_map_t& m) {
  mapper::ContourMap map;
  for (const ContourPolyline& c : ContourMapFromLcm(m).contours)
    if (c.points.size() >= (c.closed ? 3u : 2u)) map.Create(c.points, c.closed);
  return map;
}

// Points every `step` m along the walls.
std::vector<Eigen::Vector2d> WallSamples(const std::vector<Segment>& world, double step) {
  std::vector<Eigen::Vector2d> out;
  for (const Segment& s : world) {
    const double length = (s.b - s.a).norm();
    const int n = std::max(1, static_cast<int>(std::ceil(length / step)));
    for (int i = 0; i <= n; ++i) out.push_back(s.a + (s.b - s.a) * (static_cast<double>(i) / n));
  }
  return out;
}

double DistanceToWorld(const Eigen::Vector2d& p, const std::vector<Segment>& world) {
  double d = 1e300;
  for (const Segment& s : world) d = std::min(d, PointToSegmentDistance(p, s));
  return d;
}

// The judge's check for one vehicle pose that saw `before` and then `after` (the same
// definitions as sim/changing_world.h, for a single station in each world).
ScenarioCheck CheckFor(const std::vector<Segment>& before, const std::vector<Segment>& after, const Pose2& pose,
                       const ChangingWorldOptions& o) {
  ScenarioCheck c;
  c.label = "after the doors opened, live";
  c.world = 1;
  const Eigen::Vector2d from = pose.translation();
  for (const Eigen::Vector2d& p : WallSamples(after, o.sample_step)) {
    const bool seen_after = SeesWallPoint(after, from, p, o.max_view_range, o.min_view_angle);
    if (SeesWallPoint(before, from, p, o.max_view_range, o.min_view_angle)) c.must_stay.push_back({p, !seen_after});
    if (seen_after) c.must_appear.push_back({p, false});
  }
  for (const Eigen::Vector2d& q : WallSamples(before, o.sample_step)) {
    if (DistanceToWorld(q, after) < 0.02) continue;  // still there
    if (!SeesWallPoint(before, from, q, o.max_view_range, o.min_view_angle)) continue;
    // Seen through now: the ray to q goes on past it in the new world.
    const Eigen::Vector2d d = q - from;
    const auto hit = CastRay(from, std::atan2(d.y(), d.x()), after, o.max_view_range + 10.0);
    if (!hit || hit->range > d.norm() + 0.2) c.must_go.push_back({q, false});
  }
  return c;
}

using ChangingWorldMapperBusTest = testing::PrivateBusTest;

TEST_F(ChangingWorldMapperBusTest, TheLiveMapperFollowsDoorsOpenedWhileTheFleetRuns) {
  const char* url_env = url_.c_str();

  testing::TempDir dir("minenav_changing_world_mapper");
  const ChangingWorldScenario doors = DoorsOpenScenario();
  ASSERT_EQ(doors.worlds.size(), 2u);
  const std::string closed = dir / "closed.json", open = dir / "open.json";
  SaveSegmentsJson(closed, doors.worlds[0]);
  SaveSegmentsJson(open, doors.worlds[1]);
  // In room A, 4.5 m in front of the double door (x = 20, y in [4.5, 6.5]), facing it.
  const Pose2 pose(15.5, 6.5, 0.0);
  constexpr double kChangeAt = 6.0;  // s after vehicle_sim starts
  constexpr int kScansAfter = 6;     // mapped after the change before the map is judged

  LcmBus bus(url_env, 10000);
  std::vector<contour_map_t> maps;
  std::vector<pose_estimate_t> poses;
  std::vector<int64_t> scan_utimes;
  int64_t change_utime = -1;
  Subscribe<ladar_scan_t>(bus, "LADAR_SCAN", [&](const ladar_scan_t& m) { scan_utimes.push_back(m.utime); });
  Subscribe<contour_map_t>(bus, "CONTOUR_MAP", [&](const contour_map_t& m) { maps.push_back(m); });
  Subscribe<pose_estimate_t>(bus, "POSE", [&](const pose_estimate_t& m) { poses.push_back(m); });
  Subscribe<line_map_t>(bus, "SIM_WORLD", [&](const line_map_t& m) {
    if (change_utime < 0 && m.num_segments == static_cast<int32_t>(doors.worlds[1].size())) change_utime = m.utime;
  });

  // Perfect odometry: a standing vehicle's pose is then known exactly and the map frame is
  // the world frame (the first scan anchors it at its odometry pose). One 1024-point scan a
  // second: the mapper inserts every scan (its live default) and must keep up on a loaded
  // 2-core machine. The ladar and the vehicle stop once the scans needed are out, so the
  // mapper (much slower under ASan) never has a backlog to work through.
  ChildProcess mapper({MINENAV_CONTOUR_MAPPER_BIN, "--run-for", "120", "--final-refinement-rounds", "0"},
                      dir / "mapper.txt");
  // Mixed pixels off: the phantom points between an occluding corner and the wall behind
  // are the preprocessing's concern (mapper tests), not the changing world's.
  ChildProcess ladar({MINENAV_LADAR_DRIVER_BIN, "--run-for", "120", "--scan-rate", "1", "--points", "1024", "--seed", "4",
                      "--mixed-pixel-probability", "0"},
                     dir / "ladar.txt");
  ChildProcess sim({MINENAV_VEHICLE_SIM_BIN, "--run-for", "120", "--world", closed, "--world", open,
                    "--world-change-at", std::to_string(kChangeAt), "--start-pose", "15.5,6.5,0",
                    "--odometry-scale-error", "0", "--odometry-rotation-scale-error", "0",
                    "--odometry-heading-drift-per-metre", "0", "--odometry-translation-noise", "0",
                    "--odometry-rotation-noise", "0"},
                   dir / "sim.txt");
  const auto logs = [&] {
    return "\nmapper: " + ReadTextFile(dir / "mapper.txt") + "\nladar: " + ReadTextFile(dir / "ladar.txt") +
           "\nsim: " + ReadTextFile(dir / "sim.txt");
  };
  const auto after_change = [&](const std::vector<int64_t>& utimes) {
    int n = 0;
    for (const int64_t u : utimes) n += change_utime > 0 && u > change_utime ? 1 : 0;
    return n;
  };
  ASSERT_TRUE(Pump(bus, 60.0, [&] { return after_change(scan_utimes) >= kScansAfter; }))
      << scan_utimes.size() << " scans, change at " << change_utime << logs();
  ladar.Signal(SIGTERM);
  EXPECT_EQ(ladar.Wait(10.0), 0) << logs();
  // The mapper handles scans in order: once the last scan has its POSE, all have been
  // handled (a scan published before the mapper had subscribed is simply not there); its
  // map follows the POSE. vehicle_sim goes on meanwhile: the mapper pairs each scan with the
  // odometry around its utime.
  ASSERT_TRUE(Pump(bus, 120.0, [&] { return !poses.empty() && poses.back().utime >= scan_utimes.back(); }))
      << poses.size() << " poses for " << scan_utimes.size() << " scans" << logs();
  Pump(bus, 2.0, [&] { return !maps.empty() && maps.back().utime >= scan_utimes.back(); });
  sim.Signal(SIGTERM);
  EXPECT_EQ(sim.Wait(10.0), 0) << logs();
  mapper.Signal(SIGTERM);
  EXPECT_EQ(mapper.Wait(30.0), 0) << logs();
  std::vector<int64_t> pose_utimes;
  for (const auto& p : poses) pose_utimes.push_back(p.utime);

  // Every scan was mapped where the vehicle stands (it never moved).
  int refused = 0;
  for (const auto& p : poses) {
    if (!p.converged) {
      ++refused;
      continue;
    }
    EXPECT_LT(TranslationDistance(FromLcm(p.pose), pose), 0.05) << p.status;
  }
  EXPECT_EQ(refused, 0) << logs();

  // The map just before the change's first scan held the closed doors.
  const ChangingWorldOptions options;
  const ScenarioCheck check = CheckFor(doors.worlds[0], doors.worlds[1], pose, options);
  ASSERT_GT(check.must_go.size(), 20u) << "the door leaves are not in view";
  ASSERT_GT(check.must_appear.size(), check.must_stay.size()) << "room B is not in view through the door";
  ChangingWorldScenario judged = doors;
  judged.stations = {Station{pose, 0}, Station{pose, 1}};
  judged.checks = {check};
  // (A scan stamped after the last truth sample before the change is already cast in the
  // new world: stay a truth period and more away from it.)
  const contour_map_t* before = nullptr;
  for (const auto& m : maps)
    if (m.utime < change_utime - 200'000) before = &m;
  ASSERT_NE(before, nullptr) << "no CONTOUR_MAP before the change";
  const mapper::testing::CheckFigures b = mapper::testing::JudgeMap(ToContourMap(*before), judged, check);
  EXPECT_GE(b.wrongly_kept_m, 0.9 * b.must_go_m) << "the closed doors were not mapped before they opened";

  // The final map follows the new world.
  const mapper::ContourMap final_map = ToContourMap(maps.back());
  const mapper::testing::CheckFigures f = mapper::testing::JudgeMap(final_map, judged, check);
  std::cout << "before the change: door kept " << b.wrongly_kept_m << " of " << b.must_go_m << " m\n"
            << "final map (" << f.contours << " contours, " << poses.size() << " scans, " << after_change(pose_utimes)
            << " after the change): deviation mean " << f.deviation_mean << " m, max " << f.deviation_max
            << " m; coverage " << f.coverage << "; door wrongly kept " << f.wrongly_kept_m << " of " << f.must_go_m
            << " m; wall wrongly removed " << f.wrongly_removed_m << " of " << f.must_stay_m << " m (hidden "
            << f.hidden_m << " m)\n";
  const mapper::MapDeviation dev = mapper::ContourDeviation(final_map, doors.worlds[1]);
  EXPECT_EQ(dev.mean, f.deviation_mean);
  // Thresholds from measured runs (tests/README.md): kept 0.15-0.25 m of the 2.05 m of door,
  // all of it the judge's 0.1 m bands at the door's two ends, where the partition's
  // contours end; removed 0.05-0.2 m of 48.4 m, at the far room corner seen at a glancing
  // angle; coverage 0.991; deviation mean 3-6 mm, max 5-16 cm.
  EXPECT_LE(f.wrongly_kept_m, 0.3) << "door leaves seen through are still mapped";
  EXPECT_LE(f.wrongly_removed_m, 0.5) << "walls that stayed were removed";
  EXPECT_GT(f.coverage, 0.97) << "the new world is not mapped";
  EXPECT_LT(f.deviation_mean, 0.02);
  EXPECT_LT(f.deviation_max, 0.3) << "worst at " << dev.worst_point.transpose();
}

}  // namespace
}  // namespace minenav
