// The sump-shear cycle closed in simulation: the cutter library (tracker/cutter.h) drives the
// simulated miner and its cutterhead (sim/), the coal it cuts leaves the world, and the live
// contour mapper (testing/mapper_pose_source.h: sensor_driver's simulated scans of that world
// from the true pose, the mapping session inserting every scan as the cutter's fleet runs it,
// its changing-world editing on by default, each estimate out when its computation is done)
// is the cutter's only pose. A box cut of a set depth, then a slab cut of the rest of the
// entry's width beside it (thesis 6.2.1, Figure 40) to the same depth, each judged in the true
// world (ray casts against World) and in the live contour map (ray casts against its
// contours). The stops: a face that does not give (the vehicle cannot advance) and a pose that
// goes stale during the sump, each with its one-line reason.

#include <gtest/gtest.h>

#include <cstdio>
#include <functional>

#include "common/geometry.h"
#include "mapper/test_world.h"
#include "sim/cutterhead.h"
#include "sim/vehicle_sim.h"
#include "sim/world.h"
#include "tracker/cutter.h"
#include "sim/testing/mapper_pose_source.h"

namespace minenav {
namespace {

using testing::MapperPoseSource;

constexpr int64_t kT0 = 1'700'000'000'000'000;
constexpr double kFaceX = 16.0;  // the face of the dead-end entry

// A dead-end entry 6 m wide (y in [-3, 3]), the face at x = 16, a crib block by the left rib.
std::vector<Segment> EntryWorld() {
  std::vector<Segment> w = mapper::testing::Rectangle(-8, -3, kFaceX, 3);
  return mapper::testing::Concat(w, mapper::testing::Rectangle(2, 2.0, 2.6, 2.6));
}

// The mapper as the cutter's fleet runs it (tracker/cutter_bus_test.cc: contour_mapper's
// default policy, every scan inserted, so the changing-world editing sees each new face; an
// insert refits with the 20 nearest scans within 15 m, as fleet/mission.fleet has it), on
// 720-point scans with 2 cm of range noise, each estimate out 0.5 s after its scan: a fixed
// computation time, so that the test does not depend on the machine (several times the
// release build's under the sanitizers, when the cutter's 2 s limit on the pose's age would
// stop the cut).
testing::MapperPoseSourceOptions CutterMapper() {
  testing::MapperPoseSourceOptions o;
  o.ladar.num_points = 720;
  o.ladar.angular_resolution = 0.0;  // 2 pi / 720: the whole turn
  o.ladar.min_range = 0.5;
  o.ladar.range_sigma = 0.02;
  o.ladar.range_resolution = 0.0;
  o.ladar.mixed_pixel_probability = 0.0;
  o.session = mapper::MappingSessionOptions{};
  o.session.mapper.fit_scans = 20;
  o.session.mapper.local_fit_radius = 15.0;
  o.compute_time = 0.5;
  o.seed = 3;
  return o;
}

// The appendages and the cycle a little quicker than the defaults, as in the bus test (boom
// 1 m/s, shear 4 s, sump 0.04 m/s in 0.5 m steps, cusp backed up at 0.05 m/s): the depth
// reached and how it is judged do not depend on them, the test's runtime does.
VehicleSimOptions QuickVehicle() {
  VehicleSimOptions o;
  o.seed = 3;
  o.cutterhead.boom_rate = 1.0;
  o.cutterhead.shear_time = 4.0;
  return o;
}
CutterOptions QuickCutter() {
  CutterOptions o;
  o.sump_speed = 0.04;
  o.cusp_speed = 0.05;
  return o;
}

struct CutSim {
  enum class PoseSource { kMapper, kDelayedTruth };
  explicit CutSim(PoseSource source, const Pose2& start = Pose2(10.0, 0.2, 0.05),
                  const VehicleSimOptions& options = QuickVehicle(), const CutterOptions& cutter_options = QuickCutter())
      : source_(source), options_(options), world(EntryWorld()), mapper(CutterMapper()), cutter(cutter_options) {
    vehicle.emplace(options_, start);
    head.emplace(options_.cutterhead, options_.cutterhead.max_boom_height);
    last_odometry = start;  // vehicle_sim's odometry starts at the start pose: the map's frame is the world's
    if (source_ == PoseSource::kMapper) {
      Scan(kT0);  // the first scan anchors the map
      Deliver(kT0 + 1'000'000);
    } else {
      pose = StampedPose{kT0, start};
    }
  }

  int64_t now = kT0;
  PoseSource source_;
  VehicleSimOptions options_;
  World world;
  std::optional<SimulatedVehicle> vehicle;
  std::optional<Cutterhead> head;
  MapperPoseSource mapper;
  Pose2 last_odometry;
  Cutter cutter;
  std::optional<StampedPose> pose;
  std::optional<CutterState> state;
  std::optional<DriveCommand> drive;
  // Test hooks: what the vehicle does with a drive command; whether poses still arrive.
  std::function<std::optional<DriveCommand>(const std::optional<DriveCommand>&)> obstruct;
  std::function<bool()> poses_arrive = [] { return true; };
  int scans = 0, refused_scans = 0;
  std::optional<std::pair<int64_t, PoseEstimate>> pending;  // the mapper's estimate on its way

  void Scan(int64_t t) {
    const Pose2 truth = vehicle->pose();
    if (source_ == PoseSource::kDelayedTruth) {
      if (poses_arrive()) pose = StampedPose{t, truth};
      return;
    }
    const double t_s = static_cast<double>(t - kT0) * 1e-6;
    const MapperPoseSource::Output out = mapper.Scan(world.Segments(), truth, last_odometry, t, t_s);
    ++scans;
    if (!out.estimate.converged) {
      if (refused_scans++ < 5) std::printf("scan %d refused: %s\n", scans, out.estimate.status.c_str());
      return;
    }
    pending = {kT0 + static_cast<int64_t>(out.ready_at * 1e6), out.estimate};
  }
  void Deliver(int64_t t) {
    if (pending && pending->first <= t) {
      if (poses_arrive()) pose = StampedPose{pending->second.utime, pending->second.pose};
      pending.reset();
    }
  }

  // The miner set down at `at` by the test, as if driven there with perfect odometry (the
  // cut's state stays: the world, the map, the mapper, the appendages).
  void Place(const Pose2& at) {
    vehicle.emplace(options_, at);
    last_odometry = at;
    drive.reset();
  }

  // Runs at 20 Hz (cutter at 10 Hz, state at 5 Hz, scans at 1 Hz) until the cut ends or
  // `seconds` pass (all of them with `until_done` false).
  void Run(double seconds, bool until_done = true) {
    const int steps = static_cast<int>(seconds * 20);
    for (int k = 0; k < steps && (cutter.active() || k == 0 || !until_done); ++k) {
      now += 50'000;
      Deliver(now);
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

// y of the first wall hit from (16.5, y0) along -y: the side of the cut there.
double SideY(const std::vector<Segment>& walls, double y0) {
  const auto hit = CastRay(Eigen::Vector2d(kFaceX + 0.5, y0), -kPi / 2, walls, 10.0);
  return hit ? y0 - hit->range : 1e9;
}

void ExpectDepth(const std::vector<Segment>& world, const std::vector<Segment>& map, double y, double depth,
                 const std::string& cut) {
  const double world_depth = FaceX(world, y) - kFaceX;
  const double map_depth = FaceX(map, y) - kFaceX;
  std::printf("%s, y %+.1f: true depth %.3f m, in the contour map %.3f m\n", cut.c_str(), y, world_depth, map_depth);
  EXPECT_NEAR(world_depth, depth, 0.05) << cut << ": true world at y = " << y;
  EXPECT_NEAR(map_depth, depth, 0.05) << cut << ": contour map at y = " << y;
}

// A box cut of 1 m into the face found in the live map; then the slab cut (thesis 6.2.1,
// Figure 40): the rest of the entry's width on the right of the box cut, from the miner
// repositioned beside it, to the same depth. The face line on the task is the part of the face
// left uncut, as the live map shows it (from the entry's right rib to the box cut's right rib);
// the drum overlaps the box cut's free space by about 1.8 m, so it cuts coal only over the
// strip. The repositioning is the test's own placement: driving it is the tracker's (the
// 10 m miner shuffles 1.5 m across a 6 m entry in a multi-point maneuver of ~20 pieces, the
// slab_cut maneuver of path_tracker_closed_loop_test and tracker_bench, on the live mapper's
// pose), and simulating its 200-330 s here would double this test's runtime. The miner is set
// down 0.5 deg off square (its side 5 cm from the rib leaves no more) and 1 m short of the
// face, as if driven there with perfect odometry; the world, the live map, the mapper and the
// appendages carry on.
TEST(CutterSimTest, ABoxCutThenASlabCutBesideItEachEndWithinFiveCentimetresInTheWorldAndInTheLiveMap) {
  CutSim sim(CutSim::PoseSource::kMapper);
  ASSERT_TRUE(sim.pose);
  const double depth = 1.0;
  // The face is found in the live contour map straight ahead.
  ASSERT_EQ(sim.cutter.Start(CutTask{1, depth, std::nullopt}, sim.pose, sim.mapper.MapSegments(), sim.now), "");
  EXPECT_NEAR(sim.cutter.face().a.x(), kFaceX, 0.05);
  sim.Run(900.0);
  const CutterStatus& st = sim.cutter.status();
  std::printf("box cut: %s after %.0f s, %d scans (%d refused), depth %.3f m, %d cycles\n", st.message.c_str(),
              static_cast<double>(sim.now - kT0) * 1e-6, sim.scans, sim.refused_scans, st.depth, st.cycles);
  ASSERT_EQ(st.state, CutterStatus::State::kDone) << st.message;
  EXPECT_GE(st.cycles, 2);
  std::vector<Segment> map = sim.mapper.MapSegments();
  for (double y : {-1.2, -0.6, 0.0, 0.6, 1.2}) ExpectDepth(sim.world.Segments(), map, y, depth, "box cut");
  // Outside the drum's width the face stayed where it was, in the world and in the map.
  for (double y : {-2.4, 2.4}) {
    EXPECT_NEAR(FaceX(sim.world.Segments(), y), kFaceX, 1e-6);
    EXPECT_NEAR(FaceX(map, y), kFaceX, 0.05);
  }
  const double box_coal = sim.head->State(sim.now).coal_removed;
  EXPECT_NEAR(box_coal, 3.3 * depth, 3.3 * 0.05);
  EXPECT_FALSE(sim.head->State(sim.now).drum_on);
  // The miner backed out of the cut: its drum's front withdraw_gap before the old face line
  // (truly; the cutter steered on the mapper's estimate), its body clear of the cut's ribs.
  const double withdraw = sim.cutter.options().withdraw_gap;
  EXPECT_NEAR(sim.vehicle->pose().x + sim.cutter.options().reach, kFaceX - withdraw, 0.05);

  // The slab. The part of the face left on the right, as the live map shows it.
  const double rib_in_map = SideY(map, 0.0);              // the box cut's right rib
  const double rib_before = SideY(sim.world.Segments(), 0.0);
  ASSERT_GT(rib_in_map, -2.0);
  ASSERT_LT(rib_in_map, -1.0);
  const double face_in_map = FaceX(map, -2.5);
  const Segment slab_face(face_in_map, -3.0, face_in_map, rib_in_map);
  sim.Place(Pose2(kFaceX - 6.0, -1.3, DegToRad(0.5)));  // the drum: y in [-2.95, 0.35], front 1 m short
  sim.Run(3.0, false);                                    // scans of the new place
  ASSERT_TRUE(sim.pose);
  ASSERT_EQ(sim.cutter.Start(CutTask{2, depth, slab_face}, sim.pose, map, sim.now), "");
  sim.Run(900.0);
  std::printf("slab cut: %s after %.0f s in all, %d scans (%d refused), depth %.3f m, %d cycles\n",
              st.message.c_str(), static_cast<double>(sim.now - kT0) * 1e-6, sim.scans, sim.refused_scans, st.depth,
              st.cycles);
  ASSERT_EQ(st.state, CutterStatus::State::kDone) << st.message;
  map = sim.mapper.MapSegments();
  for (double y : {-2.7, -2.2, -1.7}) ExpectDepth(sim.world.Segments(), map, y, depth, "slab cut");
  // The box cut is as deep as it was, and the box cut's right rib is gone: from inside the
  // cut the first wall on the right is the slab cut's side, by the entry's rib (at the drum's
  // right edge, y = -2.95 when squared up exactly; the heading tolerance, 0.005 rad over the
  // 5 m reach, moves it by up to 2.5 cm).
  for (double y : {-1.2, 0.0, 1.2}) ExpectDepth(sim.world.Segments(), map, y, depth, "the box cut after the slab");
  const double side = SideY(sim.world.Segments(), 0.0);
  std::printf("the cut's right side: y %.3f (the box cut's rib was at %.3f; in the map %.3f)\n", side, rib_before,
              SideY(map, 0.0));
  EXPECT_NEAR(side, -2.95, 0.05) << "the drum's right edge, squared up within heading_tolerance";
  // Not asserted in the live map: its changing-world editing may leave a spurious wall inside
  // the slab cut where the box cut's rib was (seen: a 1 m contour from (16.0, -2.44) to
  // (17.0, -2.69), kept while the miner stands at the face; tracker/README.md, "Not yet"). The
  // face itself is judged at the three points above, across the strip.
  // The drum took coal only where there was coal: the strip between the box cut's rib and the
  // slab cut's side, as deep as the cut.
  const double strip = (rib_before - side) * (FaceX(sim.world.Segments(), -2.2) - kFaceX);
  const double slab_coal = sim.head->State(sim.now).coal_removed - box_coal;
  std::printf("coal: box cut %.3f m^2, slab cut %.3f m^2 (the strip: %.3f m^2)\n", box_coal, slab_coal, strip);
  EXPECT_NEAR(slab_coal, strip, 0.05 * strip);
  EXPECT_FALSE(sim.head->State(sim.now).drum_on);
  EXPECT_NEAR(sim.vehicle->pose().x + sim.cutter.options().reach, face_in_map - withdraw, 0.05)
      << "backed out of the slab cut";
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
  const std::string why = sim.cutter.Start(CutTask{4, 1.0, std::nullopt}, sim.pose, sim.mapper.MapSegments(), sim.now);
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
