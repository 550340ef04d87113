// viewer_test_log: the known log of the operator's view's browser test (viewer/browser_test.sh).
// It takes a survey log (log_tool survey: SIM_WORLD, ODOMETRY, SIM_TRUTH, LADAR_SCAN at each
// station) and adds, at each station's time, what the rest of the fleet would publish there:
// POSE (the true pose offset by a known amount, with a covariance), CONTOUR_MAP (the true walls
// sampled every 0.1 m, zlib-compressed, a new version at the first and at the middle station),
// PATH and DRIVE_PATH (straight legs through the stations), MISSION_STATUS (a survey's task
// tree, the current station running) and HEARTBEAT (two processes). A test tool: it builds a
// picture whose every element is known, so a screenshot can be checked against the walls.
//
//   viewer_test_log SURVEY.lcm OUT.lcm

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "common/file_io.h"
#include "common/node/contour_map_conversions.h"
#include "common/node/conversions.h"
#include "common/node/event_log.h"
#include "minenav/heartbeat_t.hpp"
#include "minenav/mission_status_t.hpp"
#include "minenav/path_t.hpp"

namespace minenav {
namespace {

// The estimate the log claims: truth moved by this much (m, m, rad).
constexpr double kPoseOffsetX = 0.3, kPoseOffsetY = -0.2, kPoseOffsetTheta = 0.02;

contour_map_t WallsAsContourMap(const std::vector<Segment>& walls, int64_t utime, int64_t version) {
  ContourMapMessage map;
  map.utime = utime;
  map.version = version;
  map.num_scans = static_cast<int32_t>(version);
  int64_t id = 0;
  for (const Segment& s : walls) {
    ContourPolyline c;
    c.id = id++;
    const int n = std::max(1, static_cast<int>(std::ceil((s.b - s.a).norm() / 0.1)));
    for (int i = 0; i <= n; ++i) c.points.push_back(s.a + (s.b - s.a) * (static_cast<double>(i) / n));
    map.contours.push_back(std::move(c));
  }
  return ContourMapToLcm(map, /*compress_above=*/1024);
}

path_t Legs(const std::vector<vehicle_truth_t>& stations, size_t from, size_t to, int64_t utime, int64_t request_id) {
  path_t p{};
  p.utime = utime;
  p.request_id = request_id;
  p.feasible = 1;
  p.status = "ok";
  p.start = stations[from].pose;
  for (size_t k = from + 1; k <= to && k < stations.size(); ++k) {
    path_segment_t s{};
    s.motion = path_segment_t::FORWARD;
    s.end = stations[k].pose;
    s.speed = 0.5;
    p.length += std::hypot(s.end.x - stations[k - 1].pose.x, s.end.y - stations[k - 1].pose.y);
    p.segments.push_back(s);
  }
  p.num_segments = static_cast<int32_t>(p.segments.size());
  return p;
}

mission_status_t Mission(size_t current, size_t total, int64_t utime) {
  mission_status_t m{};
  m.utime = utime;
  m.mission_id = "survey-test";
  m.state = mission_status_t::RUNNING;
  m.current_task_id = static_cast<int64_t>(current);
  m.tasks_done = static_cast<int32_t>(current);
  m.tasks_total = static_cast<int32_t>(total);
  m.progress = 0.5f;
  m.message = "driving to station " + std::to_string(current);
  m.waiting_for = "path_tracker: TASK_STATUS DONE";
  mission_node_t root{};
  root.id = 0;
  root.parent = -1;
  root.name = "sequence: survey";
  root.state = mission_node_t::RUNNING;
  root.task_id = -1;
  m.nodes.push_back(root);
  for (size_t k = 0; k < total; ++k) {
    mission_node_t n{};
    n.id = static_cast<int32_t>(k + 1);
    n.parent = 0;
    n.name = "scan station " + std::to_string(k);
    n.state = k < current ? mission_node_t::SUCCESS : k == current ? mission_node_t::RUNNING : mission_node_t::IDLE;
    n.task_id = static_cast<int64_t>(k);
    m.nodes.push_back(n);
  }
  m.num_nodes = static_cast<int32_t>(m.nodes.size());
  return m;
}

heartbeat_t Heartbeat(const std::string& process, int8_t state, const std::string& message, int64_t utime,
                      int64_t seq) {
  heartbeat_t h{};
  h.utime = utime;
  h.seq = seq;
  h.process = process;
  h.pid = 1000 + static_cast<int32_t>(process.size());
  h.state = state;
  h.message = message;
  h.messages_in = seq * 10;
  return h;
}

int Run(const std::string& in, const std::string& out) {
  CheckOutputIsNotInput("OUT", out, {in});
  std::vector<LogEvent> events;
  std::vector<vehicle_truth_t> stations;
  std::vector<Segment> walls;
  LogReader reader(in);
  while (auto e = reader.Next()) {
    std::string error;
    if (e->channel == "SIM_TRUTH") {
      vehicle_truth_t t{};
      if (!DecodeMessage(e->data.data(), static_cast<int>(e->data.size()), e->channel, &t, &error)) throw InputError(error);
      stations.push_back(t);
    } else if (e->channel == "SIM_WORLD" && walls.empty()) {
      line_map_t w{};
      if (!DecodeMessage(e->data.data(), static_cast<int>(e->data.size()), e->channel, &w, &error)) throw InputError(error);
      walls = SegmentsFromLcm(w);
    }
    events.push_back(std::move(*e));
  }
  if (stations.size() < 2 || walls.empty()) throw InputError(in + ": needs SIM_WORLD and two SIM_TRUTH stations");

  LogWriter writer(out);
  size_t station = 0;
  for (const LogEvent& e : events) {
    writer.Write(e.channel, e.timestamp, e.data.data(), static_cast<int>(e.data.size()));
    if (e.channel != "SIM_TRUTH") continue;
    const vehicle_truth_t& t = stations[station];
    const int64_t now = e.timestamp;
    pose_estimate_t pose{};
    pose.utime = t.utime;
    pose.scan_id = static_cast<int64_t>(station);
    pose.source = "test";
    pose.pose.x = t.pose.x + kPoseOffsetX;
    pose.pose.y = t.pose.y + kPoseOffsetY;
    pose.pose.theta = t.pose.theta + kPoseOffsetTheta;
    pose.covariance[0] = 0.04;   // sigma x 0.2 m
    pose.covariance[4] = 0.01;   // sigma y 0.1 m
    pose.covariance[8] = 0.0004; // sigma theta 0.02 rad
    pose.converged = 1;
    pose.status = "ok";
    writer.WriteMessage("POSE", now, pose);
    if (station == 0 || station == stations.size() / 2)
      writer.WriteMessage("CONTOUR_MAP", now, WallsAsContourMap(walls, now, station == 0 ? 1 : 2));
    writer.WriteMessage("PATH", now, Legs(stations, station, stations.size() - 1, now, 100 + static_cast<int64_t>(station)));
    writer.WriteMessage("DRIVE_PATH", now, Legs(stations, station, station + 1, now, 100 + static_cast<int64_t>(station)));
    writer.WriteMessage("MISSION_STATUS", now, Mission(station, stations.size(), now));
    const int64_t seq = static_cast<int64_t>(station) + 1;
    writer.WriteMessage("HEARTBEAT", now, Heartbeat("contour_mapper", heartbeat_t::OK, "mapping", now, seq));
    writer.WriteMessage("HEARTBEAT", now, Heartbeat("path_tracker", heartbeat_t::WARN, "waiting for a path", now, seq));
    ++station;
  }
  writer.Close();
  std::printf("%s: %lld events, %zu stations, %zu walls\n", out.c_str(),
              static_cast<long long>(writer.events_written()), stations.size(), walls.size());
  return 0;
}

}  // namespace
}  // namespace minenav

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: viewer_test_log SURVEY.lcm OUT.lcm\n");
    return 2;
  }
  try {
    return minenav::Run(argv[1], argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "viewer_test_log: error: %s\n", e.what());
    return 2;
  }
}
