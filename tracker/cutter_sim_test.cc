// The sump-shear cycle closed in simulation: the cutter library (tracker/cutter.h) drives the
// simulated miner and its cutterhead (sim/), the coal it cuts leaves the world, ray-cast scans
// of that world go through the contour mapper (mapper/contour_mapper.h, its changing-world
// editing on by default) and the mapper's pose is the cutter's only pose. A box cut of a set
// depth is judged in the true world (ray casts against World) and in the live contour map
// (ray casts against its contours). The stops: a face that does not give (the vehicle cannot
// advance) and a pose that goes stale during the sump, each with its one-line reason.

#include <gtest/gtest.h>

#include <cstdio>
#include <functional>

#include "common/geometry.h"
#include "common/odometry_chain.h"
#include "mapper/contour_mapper.h"
#include "mapper/test_world.h"
#include "sim/cutterhead.h"
#include "sim/vehicle_sim.h"
#include "sim/world.h"
#include "tracker/cutter.h"

namespace minenav {
namespace {

using mapper::ContourMapper;
using mapper::InsertResult;

constexpr int64_t kT0 = 1'700'000'000'000'000;
constexpr double kFaceX = 16.0;  // the face of the dead-end entry

// A dead-end entry 6 m wide, the face at x = 16, a crib block by the left rib.
std::vector<Segment> EntryWorld() {
  std::vector<Segment> w = mapper::testing::Rectangle(-8, -3, kFaceX, 3);
  return mapper::testing::Concat(w, mapper::testing::Rectangle(2, 2.0, 2.6, 2.6));
}

struct CutSim {
  enum class PoseSource { kMapper, kDelayedTruth };
  explicit CutSim(PoseSource source, const Pose2& start = Pose2(9.0, 0.2, 0.05)) : source_(source), world(EntryWorld()) {
    VehicleSimOptions o;
    o.seed = 3;
    vehicle.emplace(o, start);
    head.emplace(o.cutterhead, o.cutterhead.max_boom_height);
    odometry_chain.Trust(start, start);
    last_odometry = start;
    if (source_ == PoseSource::kMapper) Scan(kT0);  // the first scan makes the map's frame the world's
    else pose = StampedPose{kT0, start};
  }

  int64_t now = kT0;
  PoseSource source_;
  World world;
  std::optional<SimulatedVehicle> vehicle;
  std::optional<Cutterhead> head;
  ContourMapper mapper;
  OdometryChain odometry_chain;
  Pose2 last_odometry;
  Cutter cutter{CutterOptions{}};
  std::optional<StampedPose> pose;
  std::optional<CutterState> state;
  std::optional<DriveCommand> drive;
  // Test hooks: what the vehicle does with a drive command; whether poses still arrive.
  std::function<std::optional<DriveCommand>(const std::optional<DriveCommand>&)> obstruct;
  std::function<bool()> poses_arrive = [] { return true; };
  int scans = 0, refused_scans = 0;

  void Scan(int64_t t) {
    const Pose2 truth = vehicle->pose();
    if (source_ == PoseSource::kDelayedTruth) {
      if (poses_arrive()) pose = StampedPose{t, truth};
      return;
    }
    mapper::testing::ScanSpec spec;
    spec.num_points = 720;
    spec.range_sigma = 0.02;
    spec.seed = static_cast<unsigned>(scans + 1);
    const Pose2 initial = scans == 0 ? truth : odometry_chain.Predict(last_odometry);
    const InsertResult r = mapper.InsertScan(mapper::testing::MakeScan(world.Segments(), truth, spec), initial);
    ++scans;
    if (!r.accepted) {
      if (refused_scans++ < 5) std::printf("scan %d refused: %s\n", scans, r.reason.c_str());
      return;
    }
    odometry_chain.Trust(r.pose, last_odometry);
    if (poses_arrive()) pose = StampedPose{t, r.pose};
  }

  // Runs at 20 Hz (cutter at 10 Hz, state at 5 Hz, scans at 1 Hz) until the cut ends or
  // `seconds` pass.
  void Run(double seconds) {
    const int steps = static_cast<int>(seconds * 20);
    for (int k = 0; k < steps && (cutter.active() || k == 0); ++k) {
      now += 50'000;
      if (k % 2 == 0) {
        const Cutter::Output out = cutter.Update(now, pose, state);
        if (out.drive) {
          drive = out.drive;
          drive->utime = now;
        }
        if (out.cutter) head->Command(*out.cutter, vehicle->pose(), now);
      }
      std::optional<DriveCommand> d = drive;
      if (d) d = head->FilterDrive(*d, vehicle->pose(), world, now);
      if (obstruct) d = obstruct(d);
      const SimulatedVehicle::Tick tick = vehicle->Step(now, d);
      head->Step(0.05, tick.truth.pose, &world, now);
      last_odometry = tick.odometry.pose;
      cutter.AddOdometry(tick.odometry);
      if (k % 4 == 0) state = head->State(now);
      if (k % 20 == 10) Scan(now);
    }
  }
};

// x of the first wall hit from (4, y) along +x (past the crib block).
double FaceX(const std::vector<Segment>& walls, double y) {
  const auto hit = CastRay(Eigen::Vector2d(4.0, y), 0.0, walls, 100.0);
  return hit ? 4.0 + hit->range : -1.0;
}

std::vector<Segment> MapSegments(const ContourMapper& m) {
  std::vector<Segment> out;
  for (const auto& [id, c] : m.map().contours())
    for (int k = 0; k < c.NumSegments(); ++k) out.push_back(c.GetSegment(k));
  return out;
}

TEST(CutterSimTest, ABoxCutOfOneMetreEndsWithinFiveCentimetresInTheWorldAndInTheLiveMap) {
  CutSim sim(CutSim::PoseSource::kMapper);
  ASSERT_TRUE(sim.pose);
  const double depth = 1.0;
  // The face is found in the live contour map straight ahead.
  ASSERT_EQ(sim.cutter.Start(CutTask{1, depth, std::nullopt}, sim.pose, MapSegments(sim.mapper), sim.now), "");
  EXPECT_NEAR(sim.cutter.face().a.x(), kFaceX, 0.05);
  sim.Run(900.0);
  const CutterStatus& st = sim.cutter.status();
  std::printf("%s after %.0f s, %d scans (%d refused), depth %.3f m, %d cycles\n", st.message.c_str(),
              static_cast<double>(sim.now - kT0) * 1e-6, sim.scans, sim.refused_scans, st.depth, st.cycles);
  ASSERT_EQ(st.state, CutterStatus::State::kDone) << st.message;
  EXPECT_GE(st.cycles, 2);
  const std::vector<Segment> map = MapSegments(sim.mapper);
  for (double y : {-1.2, -0.6, 0.0, 0.6, 1.2}) {
    const double world_depth = FaceX(sim.world.Segments(), y) - kFaceX;
    const double map_depth = FaceX(map, y) - kFaceX;
    std::printf("y %+.1f: true depth %.3f m, in the contour map %.3f m\n", y, world_depth, map_depth);
    EXPECT_NEAR(world_depth, depth, 0.05) << "true world at y = " << y;
    EXPECT_NEAR(map_depth, depth, 0.05) << "contour map at y = " << y;
  }
  // Outside the drum's width the face stayed where it was, in the world and in the map.
  for (double y : {-2.4, 2.4}) {
    EXPECT_NEAR(FaceX(sim.world.Segments(), y), kFaceX, 1e-6);
    EXPECT_NEAR(FaceX(map, y), kFaceX, 0.05);
  }
  EXPECT_NEAR(sim.head->State(sim.now).coal_removed, 3.3 * depth, 3.3 * 0.05);
  EXPECT_FALSE(sim.head->State(sim.now).drum_on);
}

TEST(CutterSimTest, AFaceThatDoesNotAdvanceStopsTheCutWithTheReason) {
  CutSim sim(CutSim::PoseSource::kDelayedTruth);
  // The coal does not give: once the drum is in the face, the tracks do not move it forward.
  sim.obstruct = [&](const std::optional<DriveCommand>& d) -> std::optional<DriveCommand> {
    if (d && d->v > 0.0 && sim.head->State(sim.now).phase == CutterState::Phase::kSumping &&
        sim.vehicle->pose().x + 5.0 >= kFaceX) {
      DriveCommand stop = *d;
      stop.mode = DriveCommand::Mode::kStop;
      return stop;
    }
    return d;
  };
  const Segment face(kFaceX, -3, kFaceX, 3);
  ASSERT_EQ(sim.cutter.Start(CutTask{2, 1.0, face}, sim.pose, {}, sim.now), "");
  sim.Run(600.0);
  const CutterStatus& st = sim.cutter.status();
  EXPECT_EQ(st.state, CutterStatus::State::kFailed);
  EXPECT_EQ(st.message, "stopped: the face does not advance: 0.00 m in 15.0 s of sumping");
  EXPECT_EQ(sim.drive->mode, DriveCommand::Mode::kStop);  // the last word
  EXPECT_FALSE(sim.head->State(sim.now).drum_on);
  EXPECT_NEAR(FaceX(sim.world.Segments(), 0.0), kFaceX, 1e-9);  // nothing was cut
}

TEST(CutterSimTest, AStalePoseDuringTheSumpStopsTheTracksWithTheReason) {
  CutSim sim(CutSim::PoseSource::kDelayedTruth);
  sim.poses_arrive = [&] { return sim.head->State(sim.now).phase != CutterState::Phase::kSumping; };
  const Segment face(kFaceX, -3, kFaceX, 3);
  ASSERT_EQ(sim.cutter.Start(CutTask{3, 1.0, face}, sim.pose, {}, sim.now), "");
  sim.Run(600.0);
  const CutterStatus& st = sim.cutter.status();
  EXPECT_EQ(st.state, CutterStatus::State::kFailed);
  EXPECT_EQ(st.message, "stopped: the pose estimate is 2.1 s old while sumping (limit 2.0 s)");
  EXPECT_EQ(sim.drive->mode, DriveCommand::Mode::kStop);
  // The vehicle stopped: a little later it has not moved.
  const Pose2 at = sim.vehicle->pose();
  for (int k = 0; k < 40; ++k) sim.vehicle->Step(sim.now += 50'000, sim.drive);
  EXPECT_LT(TranslationDistance(at, sim.vehicle->pose()), 0.01);
}

TEST(CutterSimTest, ACutWithoutAFaceInReachIsRefused) {
  CutSim sim(CutSim::PoseSource::kMapper, Pose2(0.0, 0.0, 0.0));  // the face 11 m ahead of the drum
  const std::string why = sim.cutter.Start(CutTask{4, 1.0, std::nullopt}, sim.pose, MapSegments(sim.mapper), sim.now);
  EXPECT_EQ(why, "refused: no face in reach: nothing in the map within 3.0 m ahead of the cutterhead");
  EXPECT_EQ(sim.cutter.status().state, CutterStatus::State::kFailed);
  // Given the face line, the same: it is out of reach.
  EXPECT_EQ(sim.cutter.Start(CutTask{5, 1.0, Segment(kFaceX, -3, kFaceX, 3)}, sim.pose, {}, sim.now),
            "refused: no face in reach: the face is 11.00 m ahead of the cutterhead (reach 3.00 m)");
  const Cutter::Output out = sim.cutter.Update(sim.now + 100'000, sim.pose, sim.head->State(sim.now));
  EXPECT_FALSE(out.drive);  // nothing moves
  EXPECT_FALSE(out.cutter);
}

}  // namespace
}  // namespace minenav
