// The contour mapper's node without a network: batch over an event log (LogBus) and live
// through FakeBus with its background worker. Scans of a small room (mapper/test_world.h)
// with drifting odometry go in; POSE answers, CONTOUR_MAP, checkpoints and output files come
// out, compared with a MappingSession run directly on the same scans (the node must give
// its numbers, bit for bit) and with the room's true poses.

#include "mapper/contour_mapper_node.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <map>
#include <thread>

#include "common/angle.h"
#include "common/file_io.h"
#include "common/node/conversions.h"
#include "common/node/event_log.h"
#include "common/node/fake_bus.h"
#include "common/node/log_bus.h"
#include "mapper/contour_map_io.h"
#include "mapper/map_checkpoint.h"
#include "mapper/test_world.h"
#include "minenav/contour_map_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/pose_estimate_t.hpp"

namespace minenav {
namespace {

namespace fs = std::filesystem;
using mapper::testing::DriftingOdometry;
using mapper::testing::MakeScan;
using mapper::testing::ScanSpec;
using mapper::testing::SmallRoomWorld;

constexpr int64_t kT0 = 1'700'000'000'000'000;
constexpr int64_t kScanPeriod = 200'000;  // us

// A drive through the 20 x 12 m room, 0.6 m a scan, turning slowly.
std::vector<Pose2> Drive(int n) {
  std::vector<Pose2> out;
  for (int k = 0; k < n; ++k) out.emplace_back(3.0 + 0.6 * k, 9.0 - 0.2 * k, 0.3 - 0.05 * k);
  return out;
}

LadarScan Scan(const Pose2& truth, int64_t id) {
  ScanSpec spec;
  spec.num_points = 720;
  spec.range_sigma = 0.02;
  spec.seed = static_cast<unsigned>(id + 1);
  LadarScan scan = MakeScan(SmallRoomWorld(), truth, spec);
  scan.utime = kT0 + id * kScanPeriod;
  scan.scan_id = id;
  return scan;
}

odometry_t Odometry(int64_t utime, const Pose2& pose) {
  OdometryReading o;
  o.utime = utime;
  o.pose = pose;
  return ToLcm(o);
}

struct Survey {
  explicit Survey(int n) : truth(Drive(n)), odometry(DriftingOdometry(truth)) {
    for (int k = 0; k < n; ++k) scans.push_back(Scan(truth[static_cast<size_t>(k)], k));
  }
  std::vector<Pose2> truth, odometry;
  std::vector<LadarScan> scans;
};

std::vector<pose_estimate_t> DecodePoses(const std::vector<FakeBus::Message>& messages) {
  std::vector<pose_estimate_t> out;
  for (const FakeBus::Message& m : messages) {
    pose_estimate_t msg;
    std::string error;
    if (!DecodeMessage(m.data.data(), static_cast<int>(m.data.size()), m.channel, &msg, &error))
      throw std::runtime_error(error);
    out.push_back(msg);
  }
  return out;
}

// What the node must reproduce: the session on the same scans and odometry, in order, as
// they come off the bus (ladar_scan_t carries some fields as floats).
struct Reference {
  Reference(const Survey& survey, const ContourMapperNodeOptions& o) : session(o.run.session) {
    for (size_t k = 0; k < survey.scans.size(); ++k) {
      const LadarScan scan = FromLcm(ToLcm(survey.scans[k]));
      const Pose2 odometry = FromLcm(Odometry(scan.utime, survey.odometry[k])).pose;
      results.push_back(session.AddScan(scan, odometry));
    }
  }
  mapper::MappingSession session;
  std::vector<mapper::ScanResult> results;
};

class TempDir : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("contour_mapper_node_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override {
    NodeRuntime::ClearStopSignal();
    fs::remove_all(dir_);
  }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

// ---------------------------------------------------------------------------------------
// Batch: a log through LogBus, as `contour_mapper --log`.

class ContourMapperNodeBatchTest : public TempDir {
 protected:
  // Writes the survey as a log: each scan after the odometry reading stamped with it.
  std::string WriteLog(const Survey& survey) {
    const std::string path = Path("survey.lcm");
    LogWriter w(path);
    for (size_t k = 0; k < survey.scans.size(); ++k) {
      w.Write("ODOMETRY", Odometry(survey.scans[k].utime, survey.odometry[k]));
      w.Write("LADAR_SCAN", ToLcm(survey.scans[k]));
    }
    w.Close();
    return path;
  }
  // Runs the node over `log` until its end (or `on_scan` stops it); returns the exit code.
  int RunBatch(const std::string& log, const ContourMapperNodeOptions& o,
               const std::function<void(int scans)>& on_scan = {}) {
    NodeOptions node_options;
    node_options.log = log;
    node_options.heartbeat_period = 0.0;
    NodeRuntime runtime("contour_mapper", node_options);
    runtime.Start();
    runtime.log_bus()->SetPublishCallback([&](const std::string& channel, int64_t, const uint8_t* data, int size) {
      published.push_back({channel, std::vector<uint8_t>(data, data + size), 0});
    });
    ContourMapperNode node(runtime, o, OpenMappingSession(o));
    int scans = 0;
    if (on_scan) runtime.bus().Subscribe("LADAR_SCAN", [&](const RawMessage&) { on_scan(++scans); });
    const int code = node.Run();
    received = node.scans_received();
    return code;
  }
  std::vector<FakeBus::Message> On(const std::string& channel) const {
    std::vector<FakeBus::Message> out;
    for (const auto& m : published)
      if (m.channel == channel) out.push_back(m);
    return out;
  }
  std::vector<FakeBus::Message> published;
  int64_t received = 0;
};

TEST_F(ContourMapperNodeBatchTest, AnswersEveryScanAsTheSessionDoesAndWritesTheRefinedOutputsAtTheEnd) {
  const Survey survey(8);
  ContourMapperNodeOptions o;
  o.map_out = Path("map.json");
  o.poses_out = Path("poses.csv");
  o.svg_out = Path("map.svg");
  o.run.final_refinement_rounds = 3;
  ASSERT_EQ(RunBatch(WriteLog(survey), o), 0);
  EXPECT_EQ(received, 8);

  Reference reference(survey, o);
  const auto poses = DecodePoses(On("POSE"));
  ASSERT_EQ(poses.size(), 8u);
  int inserted = 0;
  for (size_t k = 0; k < poses.size(); ++k) {
    const mapper::ScanResult& r = reference.results[k];
    EXPECT_EQ(poses[k].scan_id, static_cast<int64_t>(k));
    EXPECT_EQ(poses[k].utime, survey.scans[k].utime);
    EXPECT_EQ(poses[k].source, "clue");
    EXPECT_TRUE(poses[k].converged) << k << ": " << poses[k].status;
    EXPECT_EQ(poses[k].status, std::string("ok: ") + ToString(r.outcome));
    // The node runs the session itself: the same doubles.
    EXPECT_EQ(poses[k].pose.x, r.pose.x) << k;
    EXPECT_EQ(poses[k].pose.y, r.pose.y) << k;
    EXPECT_EQ(poses[k].pose.theta, r.pose.theta) << k;
    EXPECT_EQ(poses[k].num_inliers, r.num_inliers) << k;
    // And the session is right: relative to the first scan, on the truth.
    const Pose2 est = Between(reference.results[0].pose, r.pose), tru = Between(survey.truth[0], survey.truth[k]);
    EXPECT_LT(TranslationDistance(est, tru), 0.03) << k;
    EXPECT_LT(HeadingDistance(est, tru), DegToRad(0.3)) << k;
    inserted += r.outcome == mapper::ScanOutcome::kInserted;
  }
  // One CONTOUR_MAP per insert and one after the final refinement, versions increasing.
  const auto maps = On("CONTOUR_MAP");
  ASSERT_EQ(maps.size(), static_cast<size_t>(inserted + 1));
  int64_t last_version = -1;
  for (const auto& m : maps) {
    contour_map_t msg;
    std::string error;
    ASSERT_TRUE(DecodeMessage(m.data.data(), static_cast<int>(m.data.size()), m.channel, &msg, &error)) << error;
    EXPECT_GT(msg.version, last_version);
    last_version = msg.version;
  }

  // The outputs hold the result of the final refinement of 3 rounds.
  mapper::ConcurrentRefinementOptions final_refinement = reference.session.options().mapper.refinement;
  final_refinement.max_rounds = 3;
  reference.session.RefineWith(final_refinement);
  const auto written = LoadPosesCsv(o.poses_out);
  const auto expected = reference.session.Poses();
  ASSERT_EQ(written.size(), expected.size());
  for (size_t k = 0; k < written.size(); ++k) {
    EXPECT_EQ(written[k].utime, expected[k].utime);
    EXPECT_NEAR(written[k].pose.x, expected[k].pose.x, 1e-9) << k;  // CSV digits
    EXPECT_NEAR(written[k].pose.theta, expected[k].pose.theta, 1e-9) << k;
  }
  EXPECT_EQ(mapper::LoadContourMapJson(o.map_out).NumContours(), reference.session.map().NumContours());
  EXPECT_NE(ReadFile(o.svg_out).find("<svg"), std::string::npos);
  EXPECT_FALSE(fs::exists(o.map_out + ".partial"));
}

// SIGTERM after the 3rd of 8 scans: the outputs go to FILE.partial, without the final
// refinement, and the run returns 130.
TEST_F(ContourMapperNodeBatchTest, ASignalMidLogKeepsWhatWasMappedAsPartial) {
  const Survey survey(8);
  ContourMapperNodeOptions o;
  o.map_out = Path("map.json");
  o.poses_out = Path("poses.csv");
  const int code = RunBatch(WriteLog(survey), o, [](int scans) {
    if (scans == 3) std::raise(SIGTERM);  // the runtime's handler: a stop request
  });
  EXPECT_EQ(code, kExitInterrupted);
  EXPECT_FALSE(fs::exists(o.map_out));
  EXPECT_FALSE(fs::exists(o.poses_out));
  const auto kept = LoadPosesCsv(o.poses_out + ".partial");
  ASSERT_EQ(kept.size(), 3u);
  // Unrefined: the poses the scans were answered with.
  const auto poses = DecodePoses(On("POSE"));
  ASSERT_EQ(poses.size(), 3u);
  for (size_t k = 0; k < kept.size(); ++k) EXPECT_NEAR(kept[k].pose.x, poses[k].pose.x, 1e-9);
  EXPECT_GE(mapper::LoadContourMapJson(o.map_out + ".partial").NumContours(), 1);
  EXPECT_EQ(On("CONTOUR_MAP").size(), 3u);  // the inserts; no map after a final refinement
}

// ---------------------------------------------------------------------------------------
// Live: FakeBus and a manual clock; the worker maps on its own thread.

class ContourMapperNodeLiveTest : public TempDir {
 protected:
  void Start(ContourMapperNodeOptions o) {
    options = std::move(o);
    auto owned = std::make_unique<FakeBus>();
    bus = owned.get();
    NodeOptions node_options;
    node_options.heartbeat_period = 1.0;
    runtime = std::make_unique<NodeRuntime>("contour_mapper", node_options);
    runtime->StartWith(std::move(owned), clock);
    node = std::make_unique<ContourMapperNode>(*runtime, options, OpenMappingSession(options));
    runtime->SpinOnce(0);  // starts the clock: the first heartbeat
  }
  void Inject(const LadarScan& scan, const Pose2& odometry) {
    bus->InjectMessage("ODOMETRY", Odometry(scan.utime, odometry));
    bus->InjectMessage("LADAR_SCAN", ToLcm(scan));
  }
  // Spins (10 ms of clock a pass: the outbox timer) until `n` POSE answers are out.
  std::vector<pose_estimate_t> AwaitPoses(size_t n) {
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (bus->PublishedOn("POSE").size() < n && std::chrono::steady_clock::now() < give_up) {
      clock.Advance(10'000);
      runtime->SpinOnce(0);
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return DecodePoses(bus->PublishedOn("POSE"));
  }
  void Stop() {
    runtime->RequestStop();
    runtime->Shutdown();
  }
  std::vector<heartbeat_t> Heartbeats() const { return bus->Decoded<heartbeat_t>("HEARTBEAT"); }
  // CONTOUR_MAP messages that carried a change: an unchanged map sent again for processes
  // that start late (map_republish_period) repeats the one before it byte for byte.
  size_t MapChanges() const {
    size_t changes = 0;
    const auto maps = bus->PublishedOn("CONTOUR_MAP");
    for (size_t i = 0; i < maps.size(); ++i) changes += i == 0 || maps[i].data != maps[i - 1].data;
    return changes;
  }

  ManualClock clock{kT0};
  FakeBus* bus = nullptr;
  ContourMapperNodeOptions options;
  std::unique_ptr<NodeRuntime> runtime;
  std::unique_ptr<ContourMapperNode> node;
};

// Live gives the batch answers: the worker runs the same session on the same scans.
TEST_F(ContourMapperNodeLiveTest, AnswersEveryScanAsTheSessionDoesAndWritesTheOutputsAtTheStop) {
  const Survey survey(6);
  ContourMapperNodeOptions o;
  o.map_out = Path("map.json");
  o.save_map = Path("saved.json");
  Start(o);
  for (size_t k = 0; k < survey.scans.size(); ++k) {
    Inject(survey.scans[k], survey.odometry[k]);
    AwaitPoses(k + 1);  // one at a time: none is dropped
  }
  const auto poses = AwaitPoses(6);
  Reference reference(survey, o);
  ASSERT_EQ(poses.size(), 6u);
  for (size_t k = 0; k < poses.size(); ++k) {
    EXPECT_TRUE(poses[k].converged) << poses[k].status;
    EXPECT_EQ(poses[k].pose.x, reference.results[k].pose.x) << k;
    EXPECT_EQ(poses[k].pose.theta, reference.results[k].pose.theta) << k;
  }
  EXPECT_EQ(MapChanges(), 6u);  // every scan inserted (defaults)
  EXPECT_FALSE(fs::exists(o.map_out));
  Stop();
  EXPECT_EQ(node->scans_not_mapped_at_stop(), 0);
  EXPECT_EQ(MapChanges(), 7u);  // and the refined map
  EXPECT_GE(mapper::LoadContourMapJson(o.map_out).NumContours(), 1);
  EXPECT_GE(mapper::LoadContourMapJson(o.save_map).NumContours(), 1);
  EXPECT_EQ(Heartbeats().back().state, heartbeat_t::STOPPING);
}

// A scan that does not fit, one that is malformed and one without odometry: each answered
// with converged = false and the reason, the map untouched, the next scan mapped.
TEST_F(ContourMapperNodeLiveTest, RefusedInvalidAndUnpairedScansAreAnswered) {
  const Survey survey(3);
  Start({});
  Inject(survey.scans[0], survey.odometry[0]);
  AwaitPoses(1);
  // 9 m and 120 degrees off: refused.
  Inject(survey.scans[1], survey.odometry[1] * Pose2(9.0, 0.0, DegToRad(120.0)));
  const auto refused = AwaitPoses(2);
  ASSERT_EQ(refused.size(), 2u);
  EXPECT_FALSE(refused[1].converged);
  EXPECT_EQ(refused[1].scan_id, 1);
  EXPECT_FALSE(refused[1].status.empty());
  EXPECT_EQ(MapChanges(), 1u);  // only the first scan changed the map
  // The next heartbeat says so.
  clock.Advance(1'000'000);
  runtime->SpinOnce(0);
  EXPECT_EQ(Heartbeats().back().state, heartbeat_t::WARN);
  EXPECT_EQ(Heartbeats().back().message, "last scan refused: " + refused[1].status);

  // Malformed: range limits that are not 0 <= min < max.
  LadarScan bad = survey.scans[2];
  bad.scan_id = 77;
  bad.max_range = -1.0f;
  Inject(bad, survey.odometry[2]);
  const auto invalid = AwaitPoses(3);
  EXPECT_FALSE(invalid[2].converged);
  EXPECT_EQ(invalid[2].scan_id, 77);
  EXPECT_EQ(invalid[2].status.rfind("invalid scan: ", 0), 0u) << invalid[2].status;
  EXPECT_GE(bus->counters().messages_bad, 1);

  // No odometry near it: a scan 30 s after the last reading is released without one.
  LadarScan late = survey.scans[2];
  late.scan_id = 78;
  late.utime += 30'000'000;
  bus->InjectMessage("LADAR_SCAN", ToLcm(late));
  const auto unpaired = AwaitPoses(4);
  EXPECT_FALSE(unpaired[3].converged);
  EXPECT_EQ(unpaired[3].status.rfind("no odometry within 1", 0), 0u) << unpaired[3].status;
  EXPECT_EQ(node->scans_without_odometry(), 1);

  Inject(survey.scans[2], survey.odometry[2]);
  const auto mapped = AwaitPoses(5);
  EXPECT_TRUE(mapped[4].converged) << mapped[4].status;
  Stop();
}

// A mapper slower than its scans: with room for one waiting scan, a burst pushes out the
// oldest waiting ones; each is counted, answered once, and shown in HEARTBEAT.
TEST_F(ContourMapperNodeLiveTest, AFullQueueDropsTheOldestScanCountsItAndAnswersIt) {
  const Survey survey(12);
  ContourMapperNodeOptions o;
  o.worker_queue_capacity = 1;
  o.run.final_refinement_rounds = 0;
  Start(o);
  for (size_t k = 0; k < survey.scans.size(); ++k) Inject(survey.scans[k], survey.odometry[k]);
  bus->HandleFor(0);  // the whole burst at once, in microseconds: the worker maps for ms
  const auto poses = AwaitPoses(12);
  ASSERT_EQ(poses.size(), 12u);
  std::map<int64_t, int> answers;
  int dropped = 0, mapped = 0;
  for (const auto& p : poses) {
    ++answers[p.scan_id];
    if (p.status == "not mapped: dropped, the mapper's queue of 1 scans was full") ++dropped;
    if (p.converged) ++mapped;
  }
  EXPECT_EQ(answers.size(), 12u);  // every scan answered exactly once
  for (const auto& [id, n] : answers) EXPECT_EQ(n, 1) << id;
  EXPECT_GE(dropped, 1);
  EXPECT_EQ(dropped, node->scans_dropped());
  EXPECT_EQ(dropped + mapped, 12);
  EXPECT_TRUE(poses.back().converged);  // the newest scan is never the one dropped
  clock.Advance(1'000'000);
  runtime->SpinOnce(0);
  EXPECT_EQ(Heartbeats().back().state, heartbeat_t::WARN);
  EXPECT_EQ(Heartbeats().back().message.rfind("mapper behind: " + std::to_string(dropped) + " scans dropped", 0), 0u)
      << Heartbeats().back().message;
  Stop();
}

// Told to stop with a backlog: the scan under way is finished, the queued ones are answered
// "not mapped", the checkpoint holds exactly the scans mapped, and no final refinement runs.
TEST_F(ContourMapperNodeLiveTest, AStopWithABacklogAnswersTheQueuedScansAndSkipsTheFinalRefinement) {
  const Survey survey(20);
  ContourMapperNodeOptions o;
  o.checkpoint = Path("run.ckpt");
  o.checkpoint_every = 0;
  o.map_out = Path("map.json");
  Start(o);
  for (size_t k = 0; k < survey.scans.size(); ++k) Inject(survey.scans[k], survey.odometry[k]);
  bus->HandleFor(0);
  Stop();  // at once: the worker is on its first scan or two
  const auto poses = DecodePoses(bus->PublishedOn("POSE"));
  ASSERT_EQ(poses.size(), 20u);
  int not_mapped = 0, mapped = 0;
  for (const auto& p : poses) {
    if (p.status == "not mapped: the mapper stopped") ++not_mapped;
    if (p.converged) ++mapped;
  }
  EXPECT_GT(not_mapped, 0);
  EXPECT_EQ(not_mapped, node->scans_not_mapped_at_stop());
  EXPECT_EQ(not_mapped + mapped, 20);
  const mapper::MapperCheckpoint checkpoint = mapper::LoadCheckpoint(o.checkpoint);
  EXPECT_EQ(static_cast<int>(checkpoint.scans.size()), mapped);
  // No refinement ran: every CONTOUR_MAP is an insert's; the map is written if there is one.
  EXPECT_EQ(MapChanges(), static_cast<size_t>(mapped));
  EXPECT_EQ(fs::exists(o.map_out), mapped > 0);
}

// --checkpoint-every 2: after the 2nd handled scan the checkpoint holds 2 scans, after the
// 3rd still 2, after the 4th 4; at the stop all 5.
TEST_F(ContourMapperNodeLiveTest, TheCheckpointIsWrittenEveryNHandledScans) {
  const Survey survey(5);
  ContourMapperNodeOptions o;
  o.checkpoint = Path("run.ckpt");
  o.checkpoint_every = 2;
  o.checkpoint_inserts = false;  // the cadence alone (every scan here is an insert)
  o.run.final_refinement_rounds = 0;
  Start(o);
  auto checkpointed = [&] {
    return fs::exists(o.checkpoint) ? static_cast<int>(mapper::LoadCheckpoint(o.checkpoint).scans.size()) : 0;
  };
  const int expected[] = {0, 2, 2, 4, 4};
  for (size_t k = 0; k < survey.scans.size(); ++k) {
    Inject(survey.scans[k], survey.odometry[k]);
    AwaitPoses(k + 1);  // the checkpoint is saved before the scan is answered
    EXPECT_EQ(checkpointed(), expected[k]) << "after scan " << k;
  }
  Stop();
  EXPECT_EQ(checkpointed(), 5);
  // A restart on it continues the same session.
  ContourMapperNodeOptions again = o;
  const mapper::MappingSession resumed = OpenMappingSession(again);
  EXPECT_EQ(resumed.mapper().scans().size(), 5u);
  EXPECT_EQ(resumed.state().inserted, 5);
}

// Live, every inserted scan is in the checkpoint before its POSE goes out (issue 16: a kill -9
// loses no inserted scan), whatever the cadence.
TEST_F(ContourMapperNodeLiveTest, EveryInsertedScanIsCheckpointedBeforeItsPoseGoesOut) {
  const Survey survey(4);
  ContourMapperNodeOptions o;
  o.checkpoint = Path("inserts.ckpt");
  o.checkpoint_every = 1000;
  o.run.final_refinement_rounds = 0;
  Start(o);
  for (size_t k = 0; k < survey.scans.size(); ++k) {
    Inject(survey.scans[k], survey.odometry[k]);
    const auto poses = AwaitPoses(k + 1);
    ASSERT_EQ(poses.back().status.rfind("ok: inserted", 0), 0u) << poses.back().status;
    EXPECT_EQ(mapper::LoadCheckpoint(o.checkpoint).scans.size(), k + 1) << "after scan " << k;
  }
  Stop();
}

// A process that starts late or restarts (the planner after kill -9) needs the map while the
// vehicle stands: live, an unchanged map goes out again every map_republish_period, and a
// resumed one at the start.
TEST_F(ContourMapperNodeLiveTest, AnUnchangedMapIsSentAgainForProcessesThatStartLate) {
  const Survey survey(2);
  ContourMapperNodeOptions o;
  o.checkpoint = Path("late.ckpt");
  o.run.final_refinement_rounds = 0;
  Start(o);
  Inject(survey.scans[0], survey.odometry[0]);
  AwaitPoses(1);
  const auto sent = bus->PublishedOn("CONTOUR_MAP");
  ASSERT_GE(sent.size(), 1u);
  const size_t before = sent.size();
  // Standing still: 5 s of clock in 10 ms steps, two more copies of the same bytes.
  for (int i = 0; i < 500; ++i) {
    clock.Advance(10'000);
    runtime->SpinOnce(0);
  }
  const auto after = bus->PublishedOn("CONTOUR_MAP");
  EXPECT_GE(after.size(), before + 2);
  EXPECT_LE(after.size(), before + 3);
  for (size_t i = before; i < after.size(); ++i) EXPECT_EQ(after[i].data, sent.back().data) << i;
  EXPECT_EQ(MapChanges(), 1u);
  Stop();
  node.reset();
  runtime.reset();

  // Resumed from the checkpoint: the map goes out before any scan.
  Start(o);
  ASSERT_GE(bus->PublishedOn("CONTOUR_MAP").size(), 1u) << "the resumed map was not sent at the start";
  const auto resumed = bus->Decoded<contour_map_t>("CONTOUR_MAP").front();
  EXPECT_EQ(resumed.num_scans, 1);
  EXPECT_GE(resumed.num_contours, 1);
  Stop();
  node.reset();
  runtime.reset();

  // 0: only on a change.
  o.map_republish_period = 0;
  o.checkpoint.clear();
  Start(o);
  Inject(survey.scans[0], survey.odometry[0]);
  AwaitPoses(1);
  const size_t once = bus->PublishedOn("CONTOUR_MAP").size();
  for (int i = 0; i < 500; ++i) {
    clock.Advance(10'000);
    runtime->SpinOnce(0);
  }
  EXPECT_EQ(bus->PublishedOn("CONTOUR_MAP").size(), once);
  Stop();
}

// ---------------------------------------------------------------------------------------
// Options: every key of the node reaches the node, the preset is a layer, checks at start.

// The process's schema: the preset option, the node's options, the preset loaded.
struct ProcessSchema {
  explicit ProcessSchema(const std::string& preset_name) : preset(preset_name) {
    schema.AddString("preset", &preset, "preset", mapper::MapperPresetNames());
    DeclareOptions(OptionScope(schema), options);
    mapper::LoadMapperPreset(schema, preset);
  }
  ConfigSchema schema{"contour_mapper", "test"};
  std::string preset;
  ContourMapperNodeOptions options;
};

TEST(ContourMapperNodeOptionsTest, TheFlatNamesOfBeforeAreAliasesOfTheNestedKeys) {
  ProcessSchema p("survey");
  ASSERT_EQ(p.schema.Parse(std::vector<std::string>{
                "--max-rms-distance", "0.05", "--max-correction-translation", "1.5", "--max-correction-rotation",
                "0.2", "--min-overlap-fraction", "0.3", "--splice-interior", "false", "--min-splice-length", "0.7",
                "--disappearance", "false", "--beam-divergence", "0.004", "--min-view-angle", "0.4",
                "--insert-min-translation", "0.5", "--insert-min-rotation", "0.25", "--refine-every-inserts", "3"}),
            ParseOutcome::kRun);
  const mapper::MappingSessionOptions& so = p.options.run.session;
  EXPECT_EQ(so.mapper.max_rms_distance, 0.05);
  EXPECT_EQ(so.mapper.max_correction_translation, 1.5);
  EXPECT_EQ(so.mapper.max_correction_rotation, 0.2);
  EXPECT_EQ(so.mapper.min_overlap_fraction, 0.3);
  EXPECT_FALSE(so.mapper.expansion.splice_interior);
  EXPECT_EQ(so.mapper.expansion.min_splice_length, 0.7);
  EXPECT_FALSE(so.mapper.disappearance.enabled);
  EXPECT_EQ(so.mapper.disappearance.beam_divergence, 0.004);
  EXPECT_EQ(so.mapper.disappearance.min_view_angle, 0.4);
  EXPECT_EQ(so.insert_min_translation, 0.5);
  EXPECT_EQ(so.insert_min_rotation, 0.25);
  EXPECT_EQ(so.refine_every_inserts, 3);
  // --print-config names the keys, not the aliases.
  const std::string config = p.schema.ConfigText();
  EXPECT_NE(config.find("\nmapper.max_rms_distance = 0.05\n"), std::string::npos);
  EXPECT_EQ(config.find("\nmax_rms_distance ="), std::string::npos);
}

// A value the preset sets shows in the printed configuration and is in force in the node:
// carmen's min_scan_points 30 (nested) lets a scan of 40 usable points in, which the
// survey's 50 refuses; its insert_min_translation 0.3 m (at the root) tracks a scan 0.1 m on.
TEST_F(ContourMapperNodeLiveTest, APresetValueShowsInThePrintedConfigurationAndIsInForce) {
  // 40 usable readings each, about the corner at (0, 0) seen from (10, 6): bearings -159 to
  // -139.5 degrees of the 0.5-degree scan.
  auto corner_only = [](LadarScan scan) {
    for (size_t i = 0; i < scan.ranges.size(); ++i)
      if (i < 42 || i >= 82) scan.ranges[i] = std::nanf("");
    return scan;
  };
  const LadarScan first = corner_only(Scan(Pose2(10.0, 6.0, 0.0), 0));
  const LadarScan near = corner_only(Scan(Pose2(10.1, 6.0, 0.0), 1));
  auto answers = [&](const std::string& preset) {
    ProcessSchema p(preset);
    EXPECT_EQ(p.schema.Parse(std::vector<std::string>{}), ParseOutcome::kRun);
    const std::string config = p.schema.ConfigText();  // what --print-config prints
    Start(p.options);
    Inject(first, Pose2(10.0, 6.0, 0.0));
    AwaitPoses(1);
    Inject(near, Pose2(10.1, 6.0, 0.0));
    const auto poses = AwaitPoses(2);
    Stop();
    node.reset();
    runtime.reset();
    return std::make_pair(config, poses);
  };
  const auto [carmen_config, carmen] = answers("carmen");
  EXPECT_NE(carmen_config.find("\nmapper.min_scan_points = 30\n"), std::string::npos);
  EXPECT_NE(carmen_config.find("\ninsert_min_translation = 0.3\n"), std::string::npos);
  ASSERT_EQ(carmen.size(), 2u);
  EXPECT_TRUE(carmen[0].converged) << carmen[0].status;  // 40 >= 30 usable points
  EXPECT_EQ(carmen[1].status, "ok: tracked");           // 0.1 m < 0.3 m since the last insert

  const auto [survey_config, survey] = answers("survey");
  EXPECT_NE(survey_config.find("\nmapper.min_scan_points = 50\n"), std::string::npos);
  ASSERT_EQ(survey.size(), 2u);
  for (const auto& p : survey) {
    EXPECT_FALSE(p.converged);  // 40 < 50 usable points
    EXPECT_NE(p.status.find("50"), std::string::npos) << p.status;
  }
}

TEST(ContourMapperNodeOptionsTest, OutputsNamingInputsAndInconsistentOptionsAreRefusedBeforeAnythingIsRead) {
  ContourMapperNodeOptions o;
  NodeOptions node;
  node.log = "/tmp/in.lcm";
  EXPECT_THROW(ValidateNodeOptions(o, node, ""), UsageError);  // --map-out is required with --log
  o.map_out = "/tmp/in.lcm";
  EXPECT_THROW(ValidateNodeOptions(o, node, ""), InputError);  // the map over the log
  o.map_out = "/tmp/map.json";
  o.poses_out = "/tmp/c.conf";
  EXPECT_THROW(ValidateNodeOptions(o, node, "/tmp/c.conf.partial"), InputError);  // its .partial too
  o.poses_out = "";
  o.checkpoint = "/tmp/in.lcm";
  EXPECT_THROW(ValidateNodeOptions(o, node, ""), InputError);
  o.checkpoint = "";
  o.run.session.mapper.pose.final_threshold = 5.0;  // above the initial threshold
  EXPECT_THROW(ValidateNodeOptions(o, node, ""), UsageError);
  o.run.session.mapper.pose.final_threshold = 0.1;
  EXPECT_NO_THROW(ValidateNodeOptions(o, node, ""));
}

}  // namespace
}  // namespace minenav
