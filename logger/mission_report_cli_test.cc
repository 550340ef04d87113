// log_tool mission-report end to end on a small mission log written here with LogWriter: an
// entry 20 x 6 m whose face a box cut moves by 0.80 m, a drive with estimates 5 cm off and
// odometry 5 % long, planner answers (one malformed), a refused path, a failed task, a WARN
// heartbeat, the mission's status lines and the coordinator's report. The JSON's figures are
// checked against what was put in; the PNG is a PNG of the SVG's size; bad input is refused.

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "common/auth_key_file.h"
#include "common/file_io.h"
#include "common/message_auth.h"
#include "common/node/contour_map_conversions.h"
#include "common/node/conversions.h"
#include "common/node/event_log.h"
#include "logger/log_tool_run.h"
#include "logger/mission_log.h"
#include "logger/test_logs.h"
#include "minenav/heartbeat_t.hpp"
#include "minenav/mission_status_t.hpp"
#include "minenav/task_status_t.hpp"
#include "planner/path_message.h"
#include "planner/task_plan_message.h"

namespace minenav {
namespace {

using logger_test::FileExists;
using logger_test::LogTool;
using logger_test::Quote;
using logger_test::ReadAll;
using logger_test::RunResult;
using logger_test::TempPath;

constexpr int64_t kT0 = 1000000000000000;
int64_t At(double s) { return kT0 + static_cast<int64_t>(std::llround(s * 1e6)); }

std::vector<Segment> Loop(const std::vector<Eigen::Vector2d>& p) {
  std::vector<Segment> out;
  for (size_t i = 0; i < p.size(); ++i) out.push_back(Segment(p[i], p[(i + 1) % p.size()]));
  return out;
}
const std::vector<Eigen::Vector2d> kBefore = {{0, 0}, {20, 0}, {20, 6}, {0, 6}};
const std::vector<Eigen::Vector2d> kAfter = {{0, 0}, {20, 0}, {20, 1.5}, {20.8, 1.5}, {20.8, 4.5}, {20, 4.5}, {20, 6}, {0, 6}};

double TruthX(double t) { return t <= 60.0 ? 2.0 + 0.2 * t : 14.0; }

struct MissionFiles {
  std::string log, world, map, mission;
};

mission_status_t Status(double t, int8_t state, int8_t explore) {
  mission_status_t m{};
  m.utime = At(t);
  m.mission_id = "m1";
  m.state = state;
  m.current_task_id = -1;
  m.message = "state " + std::to_string(state);
  for (const auto& [name, s] : std::vector<std::pair<std::string, int8_t>>{
           {"mission m1", mission_node_t::RUNNING}, {"explore the section", explore}}) {
    mission_node_t n{};
    n.id = static_cast<int32_t>(m.nodes.size());
    n.parent = n.id - 1;
    n.name = name;
    n.state = s;
    n.task_id = -1;
    m.nodes.push_back(n);
  }
  m.num_nodes = static_cast<int32_t>(m.nodes.size());
  return m;
}

path_t Path(double t, int64_t id, const std::string& status) {
  PlannedPath p;
  p.start = Pose2(2, 3, 0);
  p.pieces = {{Motion::kForward, 12.0, 0.0, Pose2(14, 3, 0)}};
  return PathToLcm(p, id, At(t), 0.2, status);
}

// Writes the mission's log (`bad`: one garbage POSE message too), the world, map and report.
MissionFiles WriteMission(bool bad = false) {
  MissionFiles f{TempPath("mission.lcm"), TempPath("world.json"), TempPath("map.json"), TempPath("mission.json")};
  LogWriter w(f.log);
  w.Write("SIM_WORLD", SegmentsToLcm(Loop(kBefore), At(0), 1, "world"));
  w.Write("MISSION_STATUS", Status(0, mission_status_t::WAITING, mission_node_t::IDLE));
  w.Write("MISSION_STATUS", Status(1, mission_status_t::RUNNING, mission_node_t::RUNNING));
  TaskPlanMessage message;
  message.utime = At(1);
  TaskPlan& plan = message.plan;
  plan.status = PlanStatus::kOk;
  for (const auto& [kind, x] : std::vector<std::pair<TaskKind, double>>{
           {TaskKind::kScanStation, 2.0}, {TaskKind::kScanStation, 8.0}, {TaskKind::kMove, 11.0}}) {
    Task t;
    t.id = static_cast<int64_t>(plan.tasks.size()) + 1;
    t.kind = kind;
    t.target = Pose2(x, 3, 0);
    plan.tasks.push_back(t);
  }
  w.Write("TASK_PLAN", TaskPlanToLcm(message));
  w.Write("PATH", Path(1.5, 1, "ok: 12.00 m, 1 pieces, 0 reversals, 50 expansions, 4.0 ms on map version 1"));
  w.Write("PATH", Path(1.6, 1, "ok: 12.00 m, 1 pieces, 0 reversals, 50 expansions, 4.0 ms on map version 1"));
  w.Write("DRIVE_PATH", Path(1.7, 1, "ok: 12.00 m, 1 pieces, 0 reversals, 50 expansions, 4.0 ms on map version 1"));
  w.Write("PATH", NoPathToLcm(2, At(2), "no_path: boxed in"));
  w.Write("PATH", Path(3, 3, "ok: 12.00 m, 1 pieces, 0 reversals, 70 expansions, 8.0 ms on map version 2"));
  w.Write("PATH", Path(3.5, 4, "ok: fast"));
  w.Write("DRIVE_PATH", NoPathToLcm(3, At(4), "canceled by the coordinator"));
  for (int i = 0; i <= 700; ++i) {  // 70 s at 10 Hz: 60 s of driving, then standing at x = 14
    const double t = 0.1 * i;
    const double x = TruthX(t);
    w.Write("SIM_TRUTH", ToLcm(TruthReading{At(t), i, Pose2(x, 3, 0), 0.0, 0.0}));
    OdometryReading o;
    o.utime = At(t);
    o.seq = i;
    o.pose = Pose2(2.0 + 1.05 * (x - 2.0), 3, 0);  // 5 % long
    w.Write("ODOMETRY", ToLcm(o));
    if (i % 10 == 5) {  // 1 Hz, between truth readings: 3 cm east, 4 cm north, 0.01 rad
      PoseEstimate e;
      e.utime = At(t + 0.05);
      e.scan_id = i;
      e.pose = Pose2(TruthX(t + 0.05) + 0.03, 3.04, 0.01);
      e.converged = true;
      e.status = "ok";
      w.Write("POSE", ToLcm(e));
    }
  }
  if (bad) {
    const std::vector<uint8_t> garbage = {1, 2, 3, 4, 5};
    w.Write("POSE", At(70), garbage.data(), static_cast<int>(garbage.size()));
  }
  task_status_t ts{};
  ts.utime = At(62);
  ts.task_id = 7;
  ts.state = task_status_t::FAILED;
  ts.message = "cutter: drum not turning";
  w.Write("TASK_STATUS", ts);
  w.Write("TASK_STATUS", ts);
  for (const auto& [t, state, msg] : std::vector<std::tuple<double, int8_t, std::string>>{
           {10, heartbeat_t::OK, "ok"}, {11, heartbeat_t::WARN, "2 scans refused"}, {12, heartbeat_t::WARN, "3 scans refused"}, {13, heartbeat_t::OK, "ok"}}) {
    heartbeat_t h{};
    h.utime = At(t);
    h.process = "contour_mapper";
    h.state = state;
    h.message = msg;
    w.Write("HEARTBEAT", h);
  }
  w.Write("MISSION_STATUS", Status(40, mission_status_t::RUNNING, mission_node_t::SUCCESS));
  w.Write("SIM_WORLD", SegmentsToLcm(Loop(kAfter), At(65), 2, "world after the cut"));
  ContourMapMessage map;
  map.utime = At(66);
  map.version = 9;
  map.contours = {{0, true, kAfter}};
  w.Write("CONTOUR_MAP", ContourMapToLcm(map));
  w.Write("MISSION_STATUS", Status(75, mission_status_t::DONE, mission_node_t::SUCCESS));
  w.Close();
  SaveSegmentsJson(f.world, Loop(kBefore));
  std::string points;
  for (const auto& p : kAfter) points += (points.empty() ? "" : ", ") + std::string("[") + std::to_string(p.x()) + ", " + std::to_string(p.y()) + "]";
  std::ofstream(f.map) << "{\"contours\": [{\"closed\": true, \"points\": [" << points << "]}]}\n";
  std::ofstream(f.mission) << R"json({"mission_id": "m1", "state": "done", "message": "mission done", "seconds": 74.0,
    "stations_visited": 2, "stations_failed": 0, "drives": 3, "drives_planned_ahead": 1, "replans": 0,
    "retries": 1, "resends": 2, "pauses_for_lost_processes": 0, "planning_waits_s": [0.0, 0.4, 1.2],
    "events": ["retrying 'box cut 0.80 m' (attempt 2)"],
    "subtasks": [{"id": 6, "kind": "move", "description": "into position", "target": [14.0, 3.0, 0.0],
                  "depth": 0.0, "width": 0.0, "state": "success"},
                 {"id": 7, "kind": "box_cut", "description": "box cut 0.80 m", "target": [14.0, 3.0, 0.0],
                  "depth": 0.8, "width": 3.0, "face": [20.0, 1.5, 20.0, 4.5], "state": "success"}]})json";
  return f;
}

std::string Outputs(const std::string& prefix) {
  return " --report-out " + TempPath(prefix + ".md") + " --json-out " + TempPath(prefix + ".json") + " --svg-out " +
         TempPath(prefix + ".svg") + " --png-out " + TempPath(prefix + ".png");
}

TEST(MissionReportCli, TheFiguresOfAHandMadeMission) {
  const MissionFiles f = WriteMission();
  const RunResult r = LogTool("mission-report --log " + f.log + " --world " + f.world + " --map " + f.map +
                              " --mission " + f.mission + " --note 'speed factor 1'" + Outputs("r"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(ReadAll(TempPath("r.json")));
  // Explored area: 20 x 6 m plus the 3 x 0.8 m box, all of it in the map.
  EXPECT_NEAR(j["explored_area"]["true_free_m2"].get<double>(), 122.4, 1e-6);
  EXPECT_NEAR(j["explored_area"]["known_free_m2"].get<double>(), 122.4, 0.2);
  EXPECT_GT(j["explored_area"]["explored_fraction"].get<double>(), 0.998);
  EXPECT_LT(j["explored_area"]["falsely_free_m2"].get<double>(), 0.2);
  // Map: the final world itself.
  EXPECT_EQ(j["map_accuracy"]["contours"], 1);
  EXPECT_NEAR(j["map_accuracy"]["length_m"].get<double>(), 20 + 1.5 + 0.8 + 3 + 0.8 + 1.5 + 20 + 6, 1e-6);
  EXPECT_NEAR(j["map_accuracy"]["deviation_max_m"].get<double>(), 0.0, 1e-6);
  // Poses: every estimate 5 cm and 0.01 rad off; odometry 5 % long over 12 m: 0.6 m.
  const auto& est = j["pose_error"]["estimate"];
  EXPECT_EQ(est["compared"], 70);
  EXPECT_NEAR(est["mean_m"].get<double>(), 0.05, 1e-6);
  EXPECT_NEAR(est["rms_m"].get<double>(), 0.05, 1e-6);
  EXPECT_NEAR(est["max_m"].get<double>(), 0.05, 1e-6);
  EXPECT_NEAR(est["max_heading_deg"].get<double>(), 0.01 * 180.0 / M_PI, 1e-6);
  EXPECT_EQ(j["pose_error"]["odometry"]["compared"], 701);
  EXPECT_NEAR(j["pose_error"]["odometry"]["max_m"].get<double>(), 0.6, 1e-6);
  // The cut: 0.80 m in the truth and in the map, as requested.
  ASSERT_EQ(j["cuts"].size(), 1u);
  EXPECT_EQ(j["cuts"][0]["kind"], "box_cut");
  EXPECT_NEAR(j["cuts"][0]["truth"]["median_m"].get<double>(), 0.80, 1e-9);
  EXPECT_NEAR(j["cuts"][0]["map"]["median_m"].get<double>(), 0.80, 1e-5);
  EXPECT_EQ(j["cuts"][0]["off_request"], false);
  EXPECT_EQ(j["cuts_flagged"], 0);
  // Planning: two searches (4 and 8 ms; the repeat counted once), one refusal, one line not understood.
  EXPECT_EQ(j["planning"]["searches"], 2);
  EXPECT_EQ(j["planning"]["refused"], 1);
  EXPECT_EQ(j["planning"]["unparsed"], 1);
  EXPECT_DOUBLE_EQ(j["planning"]["search_ms"]["median"].get<double>(), 6.0);
  EXPECT_DOUBLE_EQ(j["planning"]["search_ms"]["max"].get<double>(), 8.0);
  EXPECT_EQ(j["planning"]["coordinator"]["waits_zero"], 1);
  EXPECT_DOUBLE_EQ(j["planning"]["coordinator"]["waits_s"]["median"].get<double>(), 0.4);
  EXPECT_EQ(j["planning"]["coordinator"]["drives_planned_ahead"], 1);
  // Retried or refused.
  const auto& rr = j["retried_or_refused"];
  EXPECT_EQ(rr["events"].size(), 1u);
  ASSERT_EQ(rr["path_refusals"].size(), 1u);
  EXPECT_EQ(rr["path_refusals"][0]["status"], "no_path: boxed in");
  ASSERT_EQ(rr["task_failures"].size(), 1u);
  EXPECT_EQ(rr["task_failures"][0]["message"], "cutter: drum not turning");
  ASSERT_EQ(rr["heartbeat_problems"].size(), 1u);
  EXPECT_EQ(rr["heartbeat_problems"][0]["first_message"], "2 scans refused");
  EXPECT_EQ(rr["heartbeat_problems"][0]["count"], 2);
  EXPECT_EQ(rr["drive_path_cancels"], 1);
  // Times and stations.
  EXPECT_DOUBLE_EQ(j["time"]["mission_s"].get<double>(), 75.0);
  EXPECT_DOUBLE_EQ(j["time"]["exploration_s"].get<double>(), 39.0);
  EXPECT_EQ(j["time"]["final_state"], "DONE");
  EXPECT_EQ(j["stations"]["source"], "TASK_PLAN scan stations");
  EXPECT_EQ(j["stations"]["poses"].size(), 2u);
  EXPECT_EQ(j["log"]["bad_messages"], 0);
  EXPECT_EQ(j["notes"][0], "speed factor 1");

  // The report has its sections; the picture its layers; the PNG is the SVG's size.
  const std::string md = ReadAll(TempPath("r.md"));
  for (const std::string s : {"## Explored area and time", "## Map accuracy", "## Pose error", "## Cuts", "## Planning",
                              "## Retried or refused", "no_path: boxed in", "speed factor 1"})
    EXPECT_NE(md.find(s), std::string::npos) << s;
  const std::string svg = ReadAll(TempPath("r.svg"));
  EXPECT_NE(svg.find("planned paths (DRIVE_PATH)"), std::string::npos);
  const size_t root = svg.find("<svg ");
  ASSERT_NE(root, std::string::npos);
  auto attribute = [&](const std::string& key) {
    const size_t at = svg.find(" " + key + "=\"", root) + key.size() + 3;
    return std::stod(svg.substr(at, svg.find('"', at) - at));
  };
  const std::string png = ReadAll(TempPath("r.png"));
  ASSERT_GT(png.size(), 1000u);
  ASSERT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  auto be32 = [&](size_t at) {
    return (static_cast<uint32_t>(static_cast<uint8_t>(png[at])) << 24) | (static_cast<uint32_t>(static_cast<uint8_t>(png[at + 1])) << 16) |
           (static_cast<uint32_t>(static_cast<uint8_t>(png[at + 2])) << 8) | static_cast<uint32_t>(static_cast<uint8_t>(png[at + 3]));
  };
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  EXPECT_NEAR(be32(16), attribute("width"), 1.0);
  EXPECT_NEAR(be32(20), attribute("height"), 1.0);
}

TEST(MissionReportCli, WithoutTheWorldFileOrTheMapTheLogServes) {
  const MissionFiles f = WriteMission();
  // The first SIM_WORLD is the world at the start, the last CONTOUR_MAP the map; no mission report.
  const RunResult r = LogTool("mission-report --log " + f.log + " --json-out " + TempPath("w.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(ReadAll(TempPath("w.json")));
  EXPECT_NEAR(j["explored_area"]["true_free_m2"].get<double>(), 122.4, 1e-6);
  EXPECT_EQ(j["map_accuracy"]["contours"], 1);
  EXPECT_NEAR(j["map_accuracy"]["deviation_max_m"].get<double>(), 0.0, 1e-5);  // float on the wire
  EXPECT_EQ(j["cuts"].size(), 0u);
  EXPECT_TRUE(j["planning"]["coordinator"].is_null());
  EXPECT_NE(j["inputs"]["map"].get<std::string>().find("CONTOUR_MAP (version 9)"), std::string::npos);
}

TEST(MissionReportCli, ABadMessageIsCountedAndADamagedLogReadUpToTheDamage) {
  const MissionFiles f = WriteMission(true);
  const RunResult r = LogTool("mission-report --log " + f.log + " --json-out " + TempPath("b.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(ReadAll(TempPath("b.json")));
  EXPECT_EQ(j["log"]["bad_messages"], 1);
  EXPECT_NE(j["log"]["first_bad"].get<std::string>().find("POSE"), std::string::npos);
  EXPECT_EQ(j["pose_error"]["estimate"]["compared"], 70);
  // The same log cut in the middle of its last event (a logger killed while writing).
  std::string bytes = ReadAll(f.log);
  bytes.resize(bytes.size() - 10);
  const std::string cut = TempPath("cut.lcm");
  std::ofstream(cut, std::ios::binary) << bytes;
  const RunResult c = LogTool("mission-report --log " + cut + " --json-out " + TempPath("c.json"));
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const nlohmann::json k = nlohmann::json::parse(ReadAll(TempPath("c.json")));
  EXPECT_FALSE(k["log"]["damage"].get<std::string>().empty());
  EXPECT_EQ(k["pose_error"]["estimate"]["compared"], 70);
  EXPECT_TRUE(k["time"]["mission_s"].is_null());  // the DONE status was the event cut off
}

// An attacker's messages in the log (forged, replayed, tampered, unsigned planner answers on the
// signed PATH channel): read with the fleet's key, none of them enters the figures.
TEST(MissionReportCli, WithTheFleetsKeyAnAttackersMessagesAreCountedAndNotUsed) {
  const MissionFiles f = WriteMission();
  const std::string key = TempPath("fleet.key");
  const AuthKeyRing keys{{RandomAuthKey(1)}};
  SaveAuthKeyFile(key, keys);
  const std::string log = TempPath("attacked.lcm");
  {
    LogWriter w(log);
    LogReader in(f.log);
    const MissionLogAuth fleet{keys};  // its signed channels: the hand-made log's are unsigned, left out
    while (const LogEvent* e = in.NextInPlace())
      if (fleet.signed_channels.count(e->channel) == 0) w.Write(e->channel, e->timestamp, e->data.data(), static_cast<int>(e->data.size()));
    MessageSigner planner(RandomSenderId()), attacker(RandomSenderId());
    const auto sign = [](MessageSigner& by, const AuthKeyRing& k, const path_t& m) {
      const std::vector<uint8_t> body = EncodeMessage(m);
      return by.Sign(k, "PATH", body.data(), static_cast<int>(body.size()), m.utime);
    };
    const std::vector<uint8_t> good =
        sign(planner, keys, Path(1.5, 1, "ok: 12.00 m, 1 pieces, 0 reversals, 50 expansions, 4.0 ms on map version 1"));
    w.Write("PATH", At(1.5), good.data(), static_cast<int>(good.size()));
    std::vector<uint8_t> tampered = good;
    tampered[40] ^= 1;
    const std::vector<uint8_t> forged = sign(attacker, AuthKeyRing{{RandomAuthKey(1)}}, NoPathToLcm(5, At(2), "no_path: forged"));
    const std::vector<uint8_t> unsigned_answer = EncodeMessage(NoPathToLcm(6, At(2.5), "no_path: unsigned"));
    for (const std::vector<uint8_t>* m : std::vector<const std::vector<uint8_t>*>{&good, &tampered, &forged, &unsigned_answer})
      w.Write("PATH", At(3), m->data(), static_cast<int>(m->size()));
    w.Close();
  }
  const RunResult r = LogTool("mission-report --log " + log + " --key-file " + key + " --json-out " + TempPath("a.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(ReadAll(TempPath("a.json")));
  EXPECT_EQ(j["log"]["auth_refused"], 4);  // the replay of the good answer, tampered, forged, unsigned
  EXPECT_NE(j["log"]["first_auth_refused"].get<std::string>().find("PATH: replayed"), std::string::npos)
      << j["log"]["first_auth_refused"];
  EXPECT_EQ(j["log"]["bad_messages"], 0);
  EXPECT_EQ(j["planning"]["searches"], 1);
  EXPECT_EQ(j["planning"]["refused"], 0);
  EXPECT_NE(r.err.find("4 messages refused by authentication"), std::string::npos) << r.err;
  // Without the key the attacker's answers are read like any other: two refusals that never were.
  const RunResult open = LogTool("mission-report --log " + log + " --json-out " + TempPath("o.json"));
  ASSERT_EQ(open.exit_code, 0) << open.err;
  const nlohmann::json k = nlohmann::json::parse(ReadAll(TempPath("o.json")));
  EXPECT_EQ(k["log"]["auth_refused"], 0);
  EXPECT_EQ(k["planning"]["refused"], 2);
  // A key file others may read is refused, as the fleet's processes refuse it.
  chmod(key.c_str(), 0644);
  const RunResult loose = LogTool("mission-report --log " + log + " --key-file " + key + " --json-out " + TempPath("l.json"));
  EXPECT_EQ(loose.exit_code, 2) << loose.err;
}

TEST(MissionReportCli, BadInputIsRefusedWithOneLineAndNothingWritten) {
  const MissionFiles f = WriteMission();
  const std::string outs = Outputs("bad");
  const std::vector<std::string> files = {TempPath("bad.md"), TempPath("bad.json"), TempPath("bad.svg"), TempPath("bad.png")};
  auto expect_refused = [&](const RunResult& r, int code, const std::string& needle) {
    EXPECT_EQ(r.exit_code, code) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    for (const std::string& o : files) EXPECT_FALSE(FileExists(o)) << o;
  };
  expect_refused(LogTool("mission-report" + outs), 2, "--log is required");
  expect_refused(LogTool("mission-report --log " + f.log), 2, "nothing to write");
  expect_refused(LogTool("mission-report --log " + TempPath("nope.lcm") + outs), 2, "nope.lcm");
  std::ofstream(TempPath("broken.json")) << "{\"drives\": ";
  expect_refused(LogTool("mission-report --log " + f.log + " --mission " + TempPath("broken.json") + outs), 2,
                 "broken.json: not JSON");
  expect_refused(LogTool("mission-report --log " + f.log + " --json-out " + f.log), 2, "--json-out");
  // A log without SIM_WORLD needs --world.
  LogWriter w(TempPath("noworld.lcm"));
  w.Write("SIM_TRUTH", ToLcm(TruthReading{At(0), 0, Pose2(1, 1, 0), 0.0, 0.0}));
  w.Close();
  expect_refused(LogTool("mission-report --log " + TempPath("noworld.lcm") + " --map " + f.map + outs), 2,
                 "give the true world with --world");
  // No rsvg-convert on PATH: a clear line, exit 3, nothing written.
  const RunResult p = LogTool("mission-report --log " + f.log + outs, "PATH=/nonexistent");
  expect_refused(p, 3, "rsvg-convert not found");
}

}  // namespace
}  // namespace minenav
