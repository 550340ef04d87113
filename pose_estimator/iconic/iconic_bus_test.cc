// The iconic pose estimator live on a real LCM bus, inside a private network namespace
// (run through tests/bus/private_net.sh, which sets MINENAV_IN_PRIVATE_NET and
// LCM_DEFAULT_URL with a port of its own): vehicle_sim drives through the synthetic mine,
// ladar_driver scans it, iconic_pose_estimator matches every scan to the world published
// as the surveyed map (LINE_MAP) and publishes POSE_IPE, which must track SIM_TRUTH.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "common/angle.h"
#include "common/node/bus.h"
#include "common/node/conversions.h"
#include "common/node/lcm_bus.h"
#include "minenav/drive_command_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "minenav/vehicle_truth_t.hpp"
#include "tests/child_process.h"
#include "tests/temp_dir.h"
#include "tests/bus/private_bus_test.h"

namespace minenav {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using testing::ChildProcess;
using testing::ReadTextFile;

using IconicBusTest = testing::PrivateBusTest;

TEST_F(IconicBusTest, PoseIpeTracksSimTruth) {
  const char* url = url_.c_str();

  testing::TempDir dir("minenav_ipe_bus_test");
  LcmBus bus(url, 1000);
  std::map<int64_t, Pose2> truth;  // utime -> true pose
  std::vector<pose_estimate_t> estimates;
  int ipe_heartbeats = 0;
  Subscribe<vehicle_truth_t>(bus, "SIM_TRUTH", [&](const vehicle_truth_t& m) { truth[m.utime] = FromLcm(m.pose); });
  Subscribe<pose_estimate_t>(bus, "POSE_IPE", [&](const pose_estimate_t& m) { estimates.push_back(m); });
  Subscribe<heartbeat_t>(bus, "HEARTBEAT", [&](const heartbeat_t& m) {
    if (m.process == "iconic_pose_estimator") ++ipe_heartbeats;
  });

  ChildProcess ipe({MINENAV_IPE_BIN, "--mode", "surveyed", "--min-threshold", "0.15", "--initial", "chained"},
                   dir / "ipe.txt");
  ChildProcess ladar({MINENAV_LADAR_DRIVER_BIN, "--sensor", "typhoon", "--seed", "5"}, dir / "ladar.txt");
  ChildProcess sim({MINENAV_VEHICLE_SIM_BIN, "--generate", "mine", "--seed", "3", "--max-forward-speed", "0.5",
                    "--max-turn-in-place-rate", "0.3", "--odometry-scale-error", "0.05",
                    "--odometry-heading-drift-per-metre", "0.02"},
                   dir / "sim.txt");
  auto pump = [&](double seconds, const std::function<bool()>& done) {
    const auto end = Clock::now() + std::chrono::duration<double>(seconds);
    while (Clock::now() < end) {
      if (done && done()) return true;
      bus.HandleFor(10'000);
    }
    return done ? done() : true;
  };
  ASSERT_TRUE(pump(30.0, [&] { return estimates.size() >= 3; }))
      << "no POSE_IPE within 30 s\nipe: " << ReadTextFile(dir / "ipe.txt") << "\nladar: " << ReadTextFile(dir / "ladar.txt")
      << "\nsim: " << ReadTextFile(dir / "sim.txt");

  // Drive: forward 4 s, turn in place 3 s, forward 3 s, commands at 10 Hz. The odometry is
  // made poor (5 % scale error, 0.02 rad/m heading drift) so that tracking needs the map.
  struct Phase {
    int8_t mode;
    double v, omega, seconds;
  };
  const std::vector<Phase> script = {{drive_command_t::VELOCITY, 0.4, 0.0, 4.0},
                                     {drive_command_t::TURN_IN_PLACE, 0.0, 0.25, 3.0},
                                     {drive_command_t::VELOCITY, 0.4, 0.0, 3.0},
                                     {drive_command_t::STOP, 0.0, 0.0, 1.0}};
  int64_t seq = 0;
  for (const Phase& phase : script) {
    const auto end = Clock::now() + std::chrono::duration<double>(phase.seconds);
    auto next = Clock::now();
    while (Clock::now() < end) {
      drive_command_t c{};
      c.utime = seq;
      c.seq = seq++;
      c.mode = phase.mode;
      c.v = phase.v;
      c.omega = phase.omega;
      c.timeout = 0.5;
      Publish(bus, "DRIVE_COMMAND", c);
      next += std::chrono::milliseconds(100);
      while (Clock::now() < next) bus.HandleFor(5'000);
    }
  }
  pump(1.0, nullptr);
  sim.Signal(SIGTERM);
  ladar.Signal(SIGTERM);
  ipe.Signal(SIGTERM);
  EXPECT_EQ(sim.Wait(10.0), 0) << ReadTextFile(dir / "sim.txt");
  EXPECT_EQ(ladar.Wait(10.0), 0) << ReadTextFile(dir / "ladar.txt");
  EXPECT_EQ(ipe.Wait(10.0), 0) << ReadTextFile(dir / "ipe.txt");

  // Each estimate against the truth interpolated at its scan's utime (the ladar casts each
  // revolution from that pose). Most must converge within 3 cm and 0.3 deg of the truth.
  ASSERT_GE(estimates.size(), 60u) << ReadTextFile(dir / "ipe.txt");
  int compared = 0, good = 0, converged = 0;
  double worst = 0.0;
  std::map<std::string, int> not_converged;  // status -> count, printed on failure
  for (const pose_estimate_t& e : estimates) {
    const auto after = truth.lower_bound(e.utime);
    if (after == truth.end() || after == truth.begin()) continue;
    const auto before = std::prev(after);
    const double f = after->first == e.utime ? 1.0
                                              : static_cast<double>(e.utime - before->first) /
                                                    static_cast<double>(after->first - before->first);
    const Pose2 true_pose = InterpolatePose(before->second, after->second, f);
    ++compared;
    const Pose2 est = FromLcm(e.pose);
    const double err = TranslationDistance(est, true_pose);
    if (e.converged) worst = std::max(worst, err);
    converged += e.converged ? 1 : 0;
    if (!e.converged) ++not_converged[e.status];
    if (e.converged && err < 0.03 && HeadingDistance(est, true_pose) < DegToRad(0.3)) ++good;
    EXPECT_EQ(e.source, "ipe");
    EXPECT_GT(e.compute_time, 0.0f);
  }
  EXPECT_GE(compared, static_cast<int>(estimates.size()) - 2);
  std::string reasons;
  for (const auto& [status, count] : not_converged) reasons += std::to_string(count) + "x " + status + "\n";
  // A converged estimate must be right (at most one outlier); an estimate that says it
  // did not converge is honest, and on a machine loaded by the parallel test suite a few
  // do not (the reasons are printed), so 90 % must converge rather than all.
  EXPECT_GE(good, converged - 1) << "worst converged error " << worst << " m\n" << ReadTextFile(dir / "ipe.txt");
  EXPECT_GE(converged, 0.9 * compared) << converged << " of " << compared << " converged; not converged:\n"
                                       << reasons << ReadTextFile(dir / "ipe.txt");
  EXPECT_GE(ipe_heartbeats, 5);
}

}  // namespace
}  // namespace minenav
