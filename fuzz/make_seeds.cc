// make_seeds: writes the seed corpus of every fuzz target (fuzz/corpus/<target>/seed_*) and the
// LCM dictionary (fuzz/dict/lcm.dict) with the project's own writers: real messages of every
// type (ToLcm, SegmentsToLcm, ContourMapToLcm, PathToLcm, TaskPlanToLcm, ...), issue 11's hostile
// payloads (tests/hostile_messages.h) as regression inputs, short scenarios of each node's input
// channels, small maps, poses and stations, the mapper's presets as config files, the fleet
// files, a short CARMEN log (plain, gzip, bzip2), a short LCM event log and a checkpoint of a
// three-scan mapping session. Deterministic: the same files every run.
//
//   build/fuzz/bin/fuzz_make_seeds fuzz      (from the repository's root; fuzz/README.md)

#include <bzlib.h>
#include <zlib.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "common/file_io.h"
#include "common/node/contour_map_conversions.h"
#include "common/node/conversions.h"
#include "common/node/event_log.h"
#include "fuzz/node_fuzz.h"
#include "mapper/contour_map_io.h"
#include "mapper/map_checkpoint.h"
#include "mapper/mapper_presets.h"
#include "mapper/mapping_session.h"
#include "mapper/test_world.h"
#include "planner/motion.h"
#include "planner/path_message.h"
#include "planner/task_plan_message.h"
#include "tests/hostile_messages.h"
#include "tracker/cutter_conversions.h"

namespace minenav::fuzz {
namespace {

namespace fs = std::filesystem;

fs::path g_root;  // fuzz/

void WriteBytes(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream f(path, std::ios::binary);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!f) throw std::runtime_error("cannot write " + path.string());
}
void Seed(const std::string& target, const std::string& name, const std::string& bytes) {
  WriteBytes(g_root / "corpus" / target / ("seed_" + name), bytes);
}
void Seed(const std::string& target, const std::string& name, const std::vector<uint8_t>& bytes) {
  Seed(target, name, std::string(bytes.begin(), bytes.end()));
}

// ---------------------------------------------------------------------------------------
// Real messages, made by the project's own writers.

const Pose2 kStand(3.0, 9.0, 0.3);  // where the vehicle stands in SmallRoomWorld

LadarScan RoomScan(int64_t utime, int64_t scan_id, const Pose2& pose, int points = 360) {
  mapper::testing::ScanSpec spec;
  spec.num_points = points;
  spec.range_sigma = 0.01;
  spec.seed = static_cast<unsigned>(scan_id + 1);
  LadarScan s = mapper::testing::MakeScan(mapper::testing::SmallRoomWorld(), pose, spec);
  s.utime = utime;
  s.scan_id = scan_id;
  s.sensor_id = "typhoon";
  s.scan_duration = 0.1;
  return s;
}

odometry_t Odometry(int64_t utime, int64_t seq, const Pose2& pose, double v = 0.0) {
  OdometryReading o;
  o.utime = utime;
  o.seq = seq;
  o.pose = pose;
  o.v = v;
  o.covariance = Eigen::Vector3d(1e-4, 1e-4, 1e-5).asDiagonal();
  return ToLcm(o);
}

pose_estimate_t Estimate(int64_t utime, int64_t scan_id, const Pose2& pose) {
  PoseEstimate e;
  e.utime = utime;
  e.scan_id = scan_id;
  e.source = "clue";
  e.pose = pose;
  e.covariance = Eigen::Vector3d(1e-4, 1e-4, 1e-5).asDiagonal();
  e.residual = 0.02;
  e.num_points = 300;
  e.num_inliers = 280;
  e.iterations = 6;
  e.converged = true;
  e.status = "ok: tracked";
  e.compute_time = 0.01;
  return ToLcm(e);
}

// The room mapped by the contour mapper from three scans: its CONTOUR_MAP and its session.
mapper::MappingSession RoomSession() {
  mapper::MappingSession session(mapper::DefaultRunSessionOptions());
  for (int i = 0; i < 3; ++i) {
    const Pose2 pose(kStand.x + i, kStand.y, kStand.theta);
    session.AddScan(RoomScan(kFuzzT0 + i * 1'000'000, i, pose), pose);
  }
  return session;
}

contour_map_t RoomContourMap(const mapper::MappingSession& session, int compress_above, int64_t utime) {
  ContourMapMessage m;
  m.utime = utime;
  m.version = 3;
  m.num_scans = static_cast<int32_t>(session.mapper().scans().size());
  for (const auto& [id, c] : session.map().contours()) m.contours.push_back({id, c.closed, c.points});
  return ContourMapToLcm(m, compress_above);
}

// Forward 2 m, a quarter arc left, a turn in place, reverse 1 m: every kind of piece.
PlannedPath SamplePath(const Pose2& start) {
  PlannedPath p;
  p.start = start;
  const double radius = 4.0;  // Se2PlannerOptions' turn radius
  auto add = [&](Motion motion, double amount, double r) {
    const Pose2 from = p.pieces.empty() ? p.start : p.pieces.back().end;
    p.pieces.push_back({motion, amount, r, PoseAfter(from, motion, amount, r)});
  };
  add(Motion::kForward, 2.0, 0.0);
  add(Motion::kArcLeft, radius * 0.5, radius);
  add(Motion::kTurnInPlace, 0.4, 0.0);
  add(Motion::kReverse, 1.0, 0.0);
  return p;
}

path_request_t Request(int64_t utime, int64_t id, const Pose2& start, const Pose2& goal) {
  path_request_t r{};
  r.utime = utime;
  r.request_id = id;
  r.start = ToLcm(start);
  r.goal = ToLcm(goal);
  r.position_tolerance = 0.05;
  r.heading_tolerance = 0.0175;
  r.allow_reverse = true;
  r.clearance = 0.1;
  r.allow_unknown = false;
  return r;
}

task_request_t TaskRequestMessage(int64_t utime, int64_t id, TaskRequestKind kind) {
  TaskRequest q;
  q.utime = utime;
  q.request_id = id;
  q.mission_id = "fuzz";
  q.kind = kind;
  q.pose = kStand;
  q.face = Pose2(15.0, 9.0, 0.0);
  q.depth = 1.0;
  q.clearance = 0.1;
  return TaskRequestToLcm(q);
}

task_plan_t TaskPlanMessageOf(int64_t utime, int64_t request_id) {
  TaskPlanMessage m;
  m.utime = utime;
  m.plan_id = 1;
  m.request_id = request_id;
  m.mission_id = "fuzz";
  m.plan.status = PlanStatus::kOk;
  m.plan.reason = "scan station 1";
  Task move;
  move.id = 1;
  move.kind = TaskKind::kScanStation;
  move.target = Pose2(8.0, 9.0, 0.0);
  move.description = "to station 1";
  move.clearance = 0.1;
  move.appendages = Appendages::kStowed;
  Task cut;
  cut.id = 2;
  cut.kind = TaskKind::kBoxCut;
  cut.target = Pose2(14.0, 9.0, 0.0);
  cut.depth = 1.0;
  cut.width = 3.3;
  cut.depends_on = 1;
  cut.description = "box cut";
  cut.face = Segment(16.0, 10.0, 16.0, 8.0);
  cut.appendages = Appendages::kCutting;
  m.plan.tasks = {move, cut};
  return TaskPlanToLcm(m);
}

task_status_t Status(int64_t utime, int64_t task_id, int8_t state, float progress, const std::string& message) {
  task_status_t s{};
  s.utime = utime;
  s.plan_id = 1;
  s.task_id = task_id;
  s.state = state;
  s.progress = progress;
  s.message = message;
  return s;
}

drive_command_t Drive(int64_t utime, int64_t seq, DriveCommand::Mode mode, double v, double omega) {
  DriveCommand c;
  c.utime = utime;
  c.seq = seq;
  c.mode = mode;
  c.v = v;
  c.omega = omega;
  c.timeout = 0.3;
  return ToLcm(c);
}

cutter_command_t CutterCommandMessage(int64_t utime, int64_t seq, CutterCommand::Action action) {
  CutterCommand c;
  c.utime = utime;
  c.seq = seq;
  c.action = action;
  c.boom_height = 2.4;
  c.sump_depth = 0.5;
  if (action == CutterCommand::Action::kSump) c.face = Segment(16.0, 10.0, 16.0, 8.0);
  return ToLcm(c);
}

cutter_state_t CutterStateMessage(int64_t utime, CutterState::Phase phase, bool drum_on, double boom) {
  CutterState s;
  s.utime = utime;
  s.phase = phase;
  s.drum_on = drum_on;
  s.boom_height = boom;
  s.message = "";
  return ToLcm(s);
}

heartbeat_t Heartbeat(int64_t utime, const std::string& process, int8_t state) {
  heartbeat_t h{};
  h.utime = utime;
  h.seq = 1;
  h.process = process;
  h.pid = 4242;
  h.state = state;
  h.message = "ok";
  h.messages_in = 10;
  return h;
}

coordinator_command_t Operator(int64_t utime, int64_t seq, int8_t command) {
  coordinator_command_t c{};
  c.utime = utime;
  c.seq = seq;
  c.command = command;
  return c;
}

mission_status_t Mission(int64_t utime) {
  mission_status_t m{};
  m.utime = utime;
  m.mission_id = "fuzz";
  m.state = mission_status_t::RUNNING;
  m.current_task_id = 1;
  m.tasks_total = 2;
  m.progress = 0.5f;
  m.message = "driving to station 1";
  mission_node_t root{};
  root.id = 0;
  root.parent = -1;
  root.name = "sequence: survey";
  root.state = mission_node_t::RUNNING;
  root.task_id = -1;
  mission_node_t leaf = root;
  leaf.id = 1;
  leaf.parent = 0;
  leaf.name = "scan station 1";
  leaf.task_id = 1;
  m.nodes = {root, leaf};
  m.num_nodes = 2;
  return m;
}

vehicle_truth_t Truth(int64_t utime, int64_t seq, const Pose2& pose) {
  TruthReading t;
  t.utime = utime;
  t.seq = seq;
  t.pose = pose;
  t.v = 0.5;
  return ToLcm(t);
}

// ---------------------------------------------------------------------------------------

void MessageSeeds(const mapper::MappingSession& session) {
  const int64_t t = kFuzzT0;
  const std::string target = "message_decode";
  Seed(target, "ladar_scan", EncodeMessage(ToLcm(RoomScan(t, 1, kStand, 64))));
  Seed(target, "odometry", EncodeMessage(Odometry(t, 1, kStand, 0.5)));
  Seed(target, "vehicle_truth", EncodeMessage(Truth(t, 1, kStand)));
  Seed(target, "drive_command", EncodeMessage(Drive(t, 1, DriveCommand::Mode::kVelocity, 0.5, 0.1)));
  Seed(target, "pose_estimate", EncodeMessage(Estimate(t, 1, kStand)));
  Seed(target, "line_map", EncodeMessage(SegmentsToLcm(mapper::testing::SmallRoomWorld(), t, 1, "room")));
  Seed(target, "contour_map_plain", EncodeMessage(RoomContourMap(session, 1 << 30, t)));
  Seed(target, "contour_map_zlib", EncodeMessage(RoomContourMap(session, 0, t)));
  Seed(target, "path", EncodeMessage(PathToLcm(SamplePath(kStand), 7, t, 0.5, "ok")));
  Seed(target, "no_path", EncodeMessage(NoPathToLcm(8, t, "no path: goal in collision")));
  Seed(target, "path_request", EncodeMessage(Request(t, 7, kStand, Pose2(12, 9, 0))));
  Seed(target, "task_request", EncodeMessage(TaskRequestMessage(t, 3, TaskRequestKind::kAdvance)));
  Seed(target, "task_plan", EncodeMessage(TaskPlanMessageOf(t, 3)));
  Seed(target, "task_status", EncodeMessage(Status(t, 7, task_status_t::ACTIVE, 0.5f, "driving")));
  Seed(target, "cutter_command", EncodeMessage(CutterCommandMessage(t, 2, CutterCommand::Action::kSump)));
  Seed(target, "cutter_state",
       EncodeMessage(CutterStateMessage(t, CutterState::Phase::kSumping, true, 1.2)));
  Seed(target, "heartbeat", EncodeMessage(Heartbeat(t, "contour_mapper", heartbeat_t::OK)));
  Seed(target, "coordinator_command", EncodeMessage(Operator(t, 1, coordinator_command_t::START)));
  Seed(target, "mission_status", EncodeMessage(Mission(t)));
  // Issue 11's hostile payloads (tests/hostile_messages.h): regression inputs.
  using namespace minenav::testing;
  Seed(target, "issue11_scan_num_ranges_2p29", ScanWithCounts(kCount2p29, 0, t));
  Seed(target, "issue11_scan_num_intensities_2p29", ScanWithCounts(0, kCount2p29, t));
  Seed(target, "issue11_scan_num_ranges_2p28", ScanWithCounts(kCount2p28, 0, t));
  Seed(target, "issue11_contour_num_points_2p29", ContourMapWithPointCount(kCount2p29));
  Seed(target, "issue11_zlib_contour_num_points_2p29", CompressedContourMap(ContourMapWithPointCount(kCount2p29)));
  Seed(target, "issue11_contour_map_num_contours_2p24", ContourMapWithContourCount(kCount2p24));
  Seed(target, "issue11_contour_map_payload_size_max", ContourMapWithPayloadSize(kCountMax));
  Seed(target, "issue11_line_map_num_segments_2p26", LineMapWithSegmentCount(kCount2p26));
}

// Node scenarios: the channel indices are those of each target's Feed() list.
void NodeSeeds(const mapper::MappingSession& session) {
  const int64_t t = kFuzzT0;
  const std::vector<uint8_t> map_plain = EncodeMessage(RoomContourMap(session, 1 << 30, t));
  const line_map_t room = SegmentsToLcm(mapper::testing::SmallRoomWorld(), t, 1, "room");

  {  // vehicle_sim: DRIVE_COMMAND, CUTTER_COMMAND
    NodeFuzzInputWriter w;
    for (int i = 0; i < 20; ++i)
      w.Add(0, 100, Drive(t + (i + 1) * 100'000, i, DriveCommand::Mode::kVelocity, 0.5, 0.1));
    w.Add(1, 10, CutterCommandMessage(t + 2'010'000, 1, CutterCommand::Action::kDrumOn));
    w.Add(1, 10, CutterCommandMessage(t + 2'020'000, 2, CutterCommand::Action::kSetBoom));
    w.Add(0, 100, Drive(t + 2'120'000, 21, DriveCommand::Mode::kStop, 0.0, 0.0));
    Seed("vehicle_sim", "drive", w.bytes());
  }
  {  // ladar_driver: SIM_WORLD, SIM_TRUTH
    NodeFuzzInputWriter w;
    w.Add(0, 0, room);
    for (int i = 0; i < 12; ++i) w.Add(1, 50, Truth(t + (i + 1) * 50'000, i, Pose2(kStand.x + 0.02 * i, kStand.y, 0.3)));
    Seed("ladar_driver", "drive", w.bytes());
  }
  {  // iconic_pose_estimator: LADAR_SCAN, ODOMETRY, LINE_MAP, CONTOUR_MAP
    NodeFuzzInputWriter w;
    w.Add(2, 0, room);
    for (int i = 0; i < 8; ++i) {
      const int64_t now = t + (i + 1) * 50'000;
      const Pose2 pose(kStand.x + 0.02 * i, kStand.y, kStand.theta);
      if (i % 2 == 0) w.Add(0, 50, ToLcm(RoomScan(now - 10'000, i, pose, 180)));
      w.Add(1, i % 2 == 0 ? 0 : 50, Odometry(now, i, pose, 0.4));
    }
    Seed("iconic_pose_estimator", "drive", w.bytes());
    NodeFuzzInputWriter c;
    c.AddRaw(3, 0, map_plain);
    c.Add(1, 10, Odometry(t + 10'000, 0, kStand));
    c.Add(0, 10, ToLcm(RoomScan(t + 15'000, 1, kStand, 180)));
    c.Add(1, 10, Odometry(t + 20'000, 1, kStand));
    Seed("iconic_pose_estimator", "contour_map", c.bytes());
    // feature_pose_estimator: LADAR_SCAN, ODOMETRY, LINE_MAP (the same channels first).
    Seed("feature_pose_estimator", "drive", w.bytes());
  }
  {  // contour_mapper: LADAR_SCAN, ODOMETRY
    NodeFuzzInputWriter w;
    for (int i = 0; i < 4; ++i) {
      const int64_t now = t + (i + 1) * 100'000;
      const Pose2 pose(kStand.x + 0.4 * i, kStand.y, kStand.theta);
      w.Add(0, 100, ToLcm(RoomScan(now - 10'000, i, pose, 120)));
      w.Add(1, 0, Odometry(now, i, pose, 1.0));
    }
    Seed("contour_mapper", "drive", w.bytes());
  }
  {  // contour_mapper_small: what CI mutates from (fuzz/CMakeLists.txt, MUTATE_FROM): the drive
     // above costs 6.5 s an input unoptimised, two scans of 90 points 1.5 s (with 60 points
     // the survey preset inserts none).
    constexpr int kSmallScanPoints = 90;
    NodeFuzzInputWriter w;
    for (int i = 0; i < 2; ++i) {
      const int64_t now = t + (i + 1) * 100'000;
      const Pose2 pose(kStand.x + 0.4 * i, kStand.y, kStand.theta);
      w.Add(0, 100, ToLcm(RoomScan(now - 10'000, i, pose, kSmallScanPoints)));
      w.Add(1, 0, Odometry(now, i, pose, 1.0));
    }
    Seed("contour_mapper_small", "two_scans", w.bytes());
  }
  {  // path_planner: PATH_REQUEST, CONTOUR_MAP, DRIVE_PATH, POSE
    NodeFuzzInputWriter w;
    w.AddRaw(1, 0, map_plain);
    w.Add(3, 10, Estimate(t + 10'000, 1, kStand));
    w.Add(0, 10, Request(t + 20'000, 1, kStand, Pose2(12.0, 9.0, 0.0)));
    w.Add(2, 500, PathToLcm(SamplePath(kStand), 1, t + 520'000, 0.5, "ok"));
    w.Add(0, 10, Request(t + 530'000, 2, kStand, Pose2(3.0, 2.0, -1.57)));
    Seed("path_planner", "request", w.bytes());
  }
  {  // task_planner: TASK_REQUEST, CONTOUR_MAP, LINE_MAP, POSE
    NodeFuzzInputWriter w;
    w.AddRaw(1, 0, map_plain);
    w.Add(2, 0, room);
    w.Add(3, 10, Estimate(t + 10'000, 1, kStand));
    w.Add(0, 10, TaskRequestMessage(t + 20'000, 1, TaskRequestKind::kSurveyNext));
    w.Add(0, 500, TaskRequestMessage(t + 520'000, 2, TaskRequestKind::kAdvance));
    Seed("task_planner", "requests", w.bytes());
  }
  {  // path_tracker: PATH, POSE, ODOMETRY, CONTOUR_MAP, LINE_MAP
    NodeFuzzInputWriter w;
    w.AddRaw(3, 0, map_plain);
    w.Add(1, 10, Estimate(t + 10'000, 1, kStand));
    w.Add(2, 0, Odometry(t + 10'000, 1, kStand));
    w.Add(0, 10, PathToLcm(SamplePath(kStand), 41, t + 20'000, 0.5, "ok"));
    for (int i = 0; i < 20; ++i) {
      const int64_t now = t + 20'000 + (i + 1) * 50'000;
      const Pose2 pose(kStand.x + 0.025 * i * std::cos(kStand.theta), kStand.y + 0.025 * i * std::sin(kStand.theta),
                       kStand.theta);
      w.Add(2, 50, Odometry(now, i + 2, pose, 0.5));
      if (i % 4 == 0) w.Add(1, 0, Estimate(now, i, pose));
    }
    Seed("path_tracker", "drive", w.bytes());
  }
  {  // survey_client: POSE, PATH, TASK_STATUS
    NodeFuzzInputWriter w;
    w.Add(0, 10, Estimate(t + 10'000, 1, Pose2()));
    w.Add(1, 600, PathToLcm(SamplePath(Pose2()), 1, t + 610'000, 0.5, "ok"));
    w.Add(2, 100, Status(t + 710'000, 1, task_status_t::ACTIVE, 0.1f, "driving"));
    w.Add(2, 600, Status(t + 1'310'000, 1, task_status_t::DONE, 1.0f, "done"));
    Seed("survey_client", "station", w.bytes());
  }
  {  // cutter: CUT_TASK, POSE, ODOMETRY, CUTTER_STATE, CONTOUR_MAP
    NodeFuzzInputWriter w;
    w.AddRaw(4, 0, map_plain);
    w.Add(1, 10, Estimate(t + 10'000, 1, Pose2(13.0, 9.0, 0.0)));
    w.Add(2, 0, Odometry(t + 10'000, 1, Pose2(13.0, 9.0, 0.0)));
    w.Add(3, 0, CutterStateMessage(t + 10'000, CutterState::Phase::kIdle, false, 2.4));
    w.Add(0, 10, CutterCommandMessage(t + 20'000, 5, CutterCommand::Action::kSump));
    for (int i = 0; i < 10; ++i) {
      const int64_t now = t + 20'000 + (i + 1) * 100'000;
      w.Add(2, 100, Odometry(now, i + 2, Pose2(13.0 + 0.01 * i, 9.0, 0.0), 0.1));
      w.Add(3, 0, CutterStateMessage(now, CutterState::Phase::kSumping, true, 1.5));
    }
    Seed("cutter", "sump", w.bytes());
  }
  {  // coordinator: HEARTBEAT, POSE, TASK_PLAN, PATH, TASK_STATUS, CUTTER_STATE, COORDINATOR_COMMAND
    NodeFuzzInputWriter w;
    for (const char* p : {"contour_mapper", "path_planner", "path_tracker", "task_planner", "cutter"})
      w.Add(0, 0, Heartbeat(t, p, heartbeat_t::OK));
    w.Add(1, 10, Estimate(t + 10'000, 1, kStand));
    w.Add(5, 0, CutterStateMessage(t + 10'000, CutterState::Phase::kIdle, false, 2.4));
    w.Add(6, 200, Operator(t + 210'000, 1, coordinator_command_t::START));
    w.Add(2, 300, TaskPlanMessageOf(t + 510'000, 1));
    w.Add(3, 300, PathToLcm(SamplePath(kStand), 1, t + 810'000, 0.5, "ok"));
    w.Add(4, 300, Status(t + 1'110'000, 1, task_status_t::DONE, 1.0f, "done"));
    w.Add(6, 300, Operator(t + 1'410'000, 2, coordinator_command_t::PAUSE));
    Seed("coordinator", "mission", w.bytes());
  }
  {  // viewer_bridge: the channels of viewer_bridge_fuzzer.cc, then the page's command
    NodeFuzzInputWriter w;
    w.Add(0, 10, ToLcm(RoomScan(t, 1, kStand, 180)));
    w.Add(1, 10, Odometry(t, 1, kStand));
    w.Add(2, 10, Estimate(t, 1, kStand));
    w.AddRaw(3, 10, map_plain);
    w.Add(4, 10, room);
    w.Add(7, 10, PathToLcm(SamplePath(kStand), 1, t, 0.5, "ok"));
    w.Add(9, 10, Request(t, 7, kStand, Pose2(12, 9, 0)));
    w.Add(10, 10, Drive(t, 1, DriveCommand::Mode::kVelocity, 0.5, 0.1));
    w.Add(11, 10, Status(t, 7, task_status_t::ACTIVE, 0.5f, "driving"));
    w.Add(12, 10, TaskPlanMessageOf(t, 3));
    w.Add(14, 10, Mission(t));
    w.Add(15, 10, CutterStateMessage(t, CutterState::Phase::kSumping, true, 1.2));
    w.Add(17, 10, Heartbeat(t, "contour_mapper", heartbeat_t::OK));
    const std::string command = R"({"command": "PAUSE"})";
    w.AddRaw(20, 100, std::vector<uint8_t>(command.begin(), command.end()));
    Seed("viewer_bridge", "channels", w.bytes());
  }
}

void FileSeeds(const mapper::MappingSession& session) {
  Seed("segments_json", "room", SegmentsToJson(mapper::testing::SmallRoomWorld()));
  Seed("segments_json", "one", SegmentsToJson({Segment(0, 0, 1, 0)}));
  Seed("contour_map_json", "room", mapper::ContourMapToJson(session.map()));
  std::vector<StampedPose> poses;
  for (int i = 0; i < 5; ++i) poses.push_back({kFuzzT0 + i * 100'000, Pose2(0.1 * i, 0.05 * i, 0.01 * i)});
  Seed("poses_csv", "five", PosesToCsv(poses));
  Seed("stations_csv", "three", StationsToCsv({{Pose2(1, 2, 0.5), 0}, {Pose2(3, 4, -1), 1}, {Pose2(5, 6, 3), 0}}));
  // The real config files: the mapper's presets.
  for (const auto& entry : fs::directory_iterator(g_root.parent_path() / "mapper" / "presets"))
    Seed("config", entry.path().filename().string(), ReadFile(entry.path().string()));
  Seed("config", "flat", "min_threshold = 0.15\nheartbeat_period = 0.5\nscan_channel = SCANS\n");
  // The real fleet files.
  Seed("fleet_file", "mission", ReadFile((g_root.parent_path() / "fleet" / "mission.fleet").string()));
  Seed("fleet_file", "two_hosts", ReadFile((g_root.parent_path() / "tests" / "bus" / "two_hosts.fleet").string()));
  // The checkpoint of the three-scan session.
  const std::string checkpoint = mapper::EncodeCheckpoint(mapper::CheckpointOf(session));
  Seed("map_checkpoint", "three_scans", checkpoint);
  // The payload alone (map_checkpoint_fuzzer.cc frames it): magic 8, version 4, size 8 ... hash 8.
  Seed("map_checkpoint", "three_scans_payload", checkpoint.substr(20, checkpoint.size() - 28));
}

// A short CARMEN log in the formats dataset_readers/carmen_log.h reads.
std::string CarmenText() {
  std::ostringstream os;
  os << "# CARMEN Logfile\nPARAM robot_front_laser_max 50.0 nohost 0.0\n";
  os.setf(std::ios::fixed);
  os.precision(3);
  for (int i = 0; i < 3; ++i) {
    const double ts = 976052857.337530 + 0.1 * i;
    os << "ODOM " << 0.1 * i << " 0.0 0.0 0.1 0.0 0.0 " << ts << " nohost " << ts << "\n";
    os << "FLASER 181";
    for (int k = 0; k < 181; ++k) os << " " << 2.0 + 0.01 * k;
    os << " " << 0.1 * i << " 0 0 " << 0.1 * i << " 0 0 " << ts << " nohost " << ts << "\n";
  }
  os << "ROBOTLASER1 0 -1.570796 3.141593 0.017453 50.0 0.01 0 5";
  for (int k = 0; k < 5; ++k) os << " " << 3.0 + k;
  os << " 0 0.3 0 0 0.3 0 0 0.1 0 0.5 0.5 0 976052857.637530 nohost 976052857.637530\n";
  os << "TRUEPOS 0 0 0 976052857.7 nohost 976052857.7\n";
  return os.str();
}

std::string Gzip(const std::string& text) {
  z_stream z{};
  if (deflateInit2(&z, 9, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK) throw std::runtime_error("deflate");
  std::string out(deflateBound(&z, static_cast<uLong>(text.size())) + 32, '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  z.avail_in = static_cast<uInt>(text.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  if (deflate(&z, Z_FINISH) != Z_STREAM_END) throw std::runtime_error("deflate");
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

std::string Bzip2(const std::string& text) {
  std::string out(text.size() * 2 + 600, '\0');
  unsigned int size = static_cast<unsigned int>(out.size());
  if (BZ2_bzBuffToBuffCompress(out.data(), &size, const_cast<char*>(text.data()),
                               static_cast<unsigned int>(text.size()), 9, 0, 0) != BZ_OK)
    throw std::runtime_error("bzip2");
  out.resize(size);
  return out;
}

void LogSeeds(const mapper::MappingSession& session) {
  const std::string text = CarmenText();
  Seed("carmen_log", "plain.clf", text);
  Seed("carmen_log", "gzip.clf.gz", Gzip(text));
  Seed("carmen_log", "bzip2.clf.bz2", Bzip2(text));

  const fs::path path = fs::temp_directory_path() / ("minenav_fuzz_seed_" + std::to_string(getpid()) + ".lcm");
  {
    LogWriter w(path.string());
    w.Write("ODOMETRY", Odometry(kFuzzT0, 1, kStand));
    w.Write("LADAR_SCAN", ToLcm(RoomScan(kFuzzT0 + 5'000, 1, kStand, 32)));
    w.Write("POSE", Estimate(kFuzzT0 + 10'000, 1, kStand));
    w.Write("CONTOUR_MAP", RoomContourMap(session, 0, kFuzzT0 + 20'000));
    w.Close();
  }
  const std::string log = ReadFile(path.string());
  fs::remove(path);
  Seed("event_log", "four_events.lcm", log);
  Seed("event_log", "cut_short.lcm", log.substr(0, log.size() - 7));
}

// Every type's fingerprint (big-endian, as on the wire) and the IEEE patterns of hostile numbers.
void LcmDictionary() {
  std::ostringstream os;
  os << "# Generated by fuzz/make_seeds.cc: fingerprints of the message types and hostile numbers.\n";
  auto bytes = [&](const std::string& name, uint64_t v, int n) {
    os << name << "=\"";
    for (int i = n - 1; i >= 0; --i) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", static_cast<unsigned>((v >> (8 * i)) & 0xff));
      os << hex;
    }
    os << "\"\n";
  };
  auto hash = [&](const std::string& name, int64_t h) { bytes("fp_" + name, static_cast<uint64_t>(h), 8); };
  hash("contour_map_t", contour_map_t::getHash());
  hash("coordinator_command_t", coordinator_command_t::getHash());
  hash("cutter_command_t", cutter_command_t::getHash());
  hash("cutter_state_t", cutter_state_t::getHash());
  hash("drive_command_t", drive_command_t::getHash());
  hash("heartbeat_t", heartbeat_t::getHash());
  hash("ladar_scan_t", ladar_scan_t::getHash());
  hash("line_map_t", line_map_t::getHash());
  hash("mission_status_t", mission_status_t::getHash());
  hash("odometry_t", odometry_t::getHash());
  hash("path_request_t", path_request_t::getHash());
  hash("path_t", path_t::getHash());
  hash("pose_estimate_t", pose_estimate_t::getHash());
  hash("task_plan_t", task_plan_t::getHash());
  hash("task_request_t", task_request_t::getHash());
  hash("task_status_t", task_status_t::getHash());
  hash("vehicle_truth_t", vehicle_truth_t::getHash());
  auto f64 = [&](const std::string& name, double d) {
    uint64_t v;
    std::memcpy(&v, &d, 8);
    bytes(name, v, 8);
  };
  auto f32 = [&](const std::string& name, float f) {
    uint32_t v;
    std::memcpy(&v, &f, 4);
    bytes(name, v, 4);
  };
  f64("f64_nan", std::nan(""));
  f64("f64_inf", INFINITY);
  f64("f64_minus_inf", -INFINITY);
  f64("f64_huge", 1e300);
  f64("f64_denormal", 4.9e-324);
  f32("f32_nan", std::nanf(""));
  f32("f32_inf", INFINITY);
  f32("f32_huge", 3e38f);
  bytes("i64_max", 0x7fffffffffffffffull, 8);
  bytes("i64_min", 0x8000000000000000ull, 8);
  bytes("i32_max", 0x7fffffffu, 4);
  bytes("i32_min", 0x80000000u, 4);
  bytes("i32_minus_one", 0xffffffffu, 4);
  bytes("t0_plus_1h", static_cast<uint64_t>(kFuzzT0 + 3'600'000'000), 8);
  bytes("t0_minus_1h", static_cast<uint64_t>(kFuzzT0 - 3'600'000'000), 8);
  WriteBytes(g_root / "dict" / "lcm.dict", os.str());
}

}  // namespace
}  // namespace minenav::fuzz

int main(int argc, char** argv) {
  using namespace minenav::fuzz;
  if (argc != 2) {
    std::cerr << "usage: fuzz_make_seeds FUZZ_DIR   (the repository's fuzz/ folder)\n";
    return 2;
  }
  g_root = argv[1];
  if (!std::filesystem::exists(g_root / "CMakeLists.txt")) {
    std::cerr << "fuzz_make_seeds: " << g_root << " is not the repository's fuzz/ folder\n";
    return 2;
  }
  const minenav::mapper::MappingSession session = RoomSession();
  MessageSeeds(session);
  NodeSeeds(session);
  FileSeeds(session);
  LogSeeds(session);
  LcmDictionary();
  std::cout << "seeds written under " << (g_root / "corpus") << ", dictionary " << (g_root / "dict" / "lcm.dict")
            << "\n";
  return 0;
}
