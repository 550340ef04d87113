#include "evaluation/mission_evaluation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <tuple>

#include "common/angle.h"
#include "common/config.h"

namespace minenav {

namespace {

std::string Fixed(double v, int digits = 2) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

// Most cells of the explored-area grid (a 400 m x 400 m section at 0.2 m).
constexpr double kMaxAreaCells = 4e6;

double Seconds(int64_t from, int64_t to) { return static_cast<double>(to - from) * 1e-6; }

constexpr MissionState kEndStates[] = {MissionState::kDone, MissionState::kFailed, MissionState::kAborted};

bool IsEnd(MissionState s) {
  for (MissionState end : kEndStates)
    if (s == end) return true;
  return false;
}

// The same for a state as the coordinator's report names it ("DONE", ...).
bool IsEndName(const std::string& name) {
  for (MissionState end : kEndStates)
    if (name == ToString(end)) return true;
  return false;
}

// task_status_t's state names (the coordinator has none for TaskState).
const char* TaskStateName(TaskState s) {
  switch (s) {
    case TaskState::kPending: return "PENDING";
    case TaskState::kActive: return "ACTIVE";
    case TaskState::kDone: return "DONE";
    case TaskState::kFailed: return "FAILED";
    case TaskState::kCanceled: return "CANCELED";
  }
  return "unknown";
}

}  // namespace

void DeclareOptions(OptionScope scope, MissionEvaluationOptions& o) {
  scope.AddDouble("area_cell", &o.area_cell, "m", "cell of the explored-area grid", 0.02, 5.0);
  scope.AddDouble("area_margin", &o.area_margin, "m", "grid margin around the true world and the map", 0.0, 100.0);
  scope.AddDouble("deviation_step", &o.deviation_step, "m", "contour sampling step of the map accuracy", 0.001, 10.0);
  scope.AddInt64("max_truth_gap_us", &o.max_truth_gap_us,
                 "a pose is compared with the truth interpolated between readings at most twice this apart [us]", 0,
                 int64_t{3600} * 1000000);
  scope.AddDouble("standing_time", &o.standing_time, "s",
                  "without TASK_PLAN scan stations: where the truth stood still this long is a station", 0.1, 3600.0);
  scope.AddDouble("standing_motion", &o.standing_motion, "m", "... moving less than this", 0.0, 10.0);
  const OptionScope cut = scope.Nested("cut");
  cut.AddDouble("inner_from", &o.cut.inner_from, "", "fraction of the face's length where the depth rays start", 0.0,
                1.0);
  cut.AddDouble("inner_to", &o.cut.inner_to, "", "fraction of the face's length where they end", 0.0, 1.0);
  cut.AddInt("rays", &o.cut.rays, "depth rays across the face", 1, 1000);
  cut.AddDouble("back_off", &o.cut.back_off, "m", "the rays start this far behind the face", 0.01, 100.0);
  cut.AddDouble("reach", &o.cut.reach, "m", "how far past the face a ray looks for the new face", 0.1, 1000.0);
  scope.AddDouble("cut_tolerance", &o.cut_tolerance, "m", "a cut off its requested depth by more is flagged", 0.0,
                  10.0);
  DeclareOptions(scope.Nested("free_space"), o.free_space);
}

// -------------------------------------------------------------------------------- figures

TimeFigures MissionTimes(const MissionRecord& log, const MissionReport* report) {
  TimeFigures t;
  t.log_s = log.events > 0 ? Seconds(log.first_utime, log.last_utime) : 0.0;
  std::optional<int64_t> start, end, explore_start, explore_end;
  for (const MissionStatusLine& s : log.mission_status) {
    if (!start && s.state != MissionState::kIdle) start = s.utime;
    if (start && !end && IsEnd(s.state)) end = s.utime;
    for (const MissionNodeLine& n : s.nodes) {
      if (n.name.rfind("explore", 0) != 0) continue;
      if (t.exploration_result.empty()) t.exploration_result = "unfinished";
      if (!explore_start && n.state == BtStatus::kRunning) explore_start = s.utime;
      if (explore_start && !explore_end &&
          (n.state == BtStatus::kSuccess || n.state == BtStatus::kFailure)) {
        explore_end = s.utime;
        t.exploration_result = ToString(n.state);
      }
      break;  // the first exploration leaf only
    }
  }
  if (start && end) t.mission_s = Seconds(*start, *end);
  if (explore_start && explore_end) t.exploration_s = Seconds(*explore_start, *explore_end);
  if (!log.mission_status.empty()) {
    t.final_state = ToString(log.mission_status.back().state);
    t.final_message = log.mission_status.back().message;
  }
  if (report && !report->state.empty() && !end) {
    t.final_state = report->state;
    t.final_message = report->message;
    if (start && IsEndName(report->state))
      t.mission_s = Seconds(*start, log.last_utime);  // ended after the log's last status
  }
  return t;
}

std::vector<CutFigures> MeasureCuts(const std::vector<MissionSubtask>& subtasks, const std::vector<Segment>& initial,
                                    const std::vector<Segment>& final_world, const std::vector<Segment>& map_walls,
                                    const CutDepthOptions& options, double tolerance) {
  std::vector<CutFigures> out;
  const StaticSegmentIndex before(initial), after(final_world), map(map_walls);
  for (const MissionSubtask& s : subtasks) {
    if (s.kind != "box_cut" && s.kind != "slab_cut") continue;
    CutFigures c;
    c.id = s.id;
    c.kind = s.kind;
    c.description = s.description;
    c.state = s.state;
    c.requested_m = s.depth;
    c.target = s.target;
    c.face = s.face;
    if (!s.face) {
      c.note = "no face in the mission's report";
      c.off_request = c.map_off = true;
      out.push_back(c);
      continue;
    }
    const Eigen::Vector2d advance(std::cos(s.target.theta), std::sin(s.target.theta));
    c.truth = MeasureFaceAdvance(*s.face, advance, before, after, options);
    c.map = MeasureFaceAdvance(*s.face, advance, before, map, options);
    c.off_request = c.truth.hits == 0 || std::abs(c.truth.median - c.requested_m) > tolerance;
    // Did the map follow the cut? Judged against what was cut, not against the request (that is
    // off_request's): a cut 4.9 cm deep of a 5 cm tolerance, mapped 0.5 cm deeper still, is a
    // true map (the CI mission with an attack, 2026-12-03).
    c.map_off = c.map.hits == 0 || c.truth.hits == 0 || std::abs(c.map.median - c.truth.median) > tolerance;
    if (c.truth.hits == 0) c.note = "no ray met the face both before and after";
    out.push_back(c);
  }
  return out;
}

PlanningFigures MeasurePlanning(const std::vector<LoggedPath>& answers, const MissionReport* mission) {
  PlanningFigures p;
  // The planner answers a repeated request again with the same message: count each once.
  std::set<std::tuple<int64_t, bool, std::string>> seen;
  std::vector<double> ms;
  for (const LoggedPath& a : answers) {
    if (!seen.insert({a.request_id, a.feasible, a.status}).second) continue;
    ++p.answers;
    if (!a.feasible) {
      ++p.refused;
      continue;
    }
    const std::optional<PlannerSearch> s = ParsePlannerStatus(a.status);
    if (!s) {
      ++p.unparsed;
      if (p.unparsed_examples.size() < 5) p.unparsed_examples.push_back(a.status.substr(0, 200));
      continue;
    }
    ++p.searches;
    p.replanned += s->replanned ? 1 : 0;
    ms.push_back(s->ms);
  }
  p.search_ms = Summarize(ms);
  if (mission) {
    p.have_mission = true;
    p.drives = mission->drives;
    p.drives_planned_ahead = mission->drives_planned_ahead;
    p.waits_s = Summarize(mission->planning_waits_s);
    p.waits_zero = static_cast<int>(
        std::count(mission->planning_waits_s.begin(), mission->planning_waits_s.end(), 0.0));
  }
  return p;
}

RefusalFigures MeasureRefusals(const MissionRecord& log, const MissionReport* mission) {
  RefusalFigures r;
  if (mission) {
    r.events = mission->events;
    r.retries = mission->retries;
    r.replans = mission->replans;
    r.resends = mission->resends;
    r.pauses = mission->pauses_for_lost_processes;
  }
  std::set<std::pair<int64_t, std::string>> paths;
  for (const LoggedPath& a : log.planner_paths)
    if (!a.feasible && paths.insert({a.request_id, a.status}).second)
      r.path_refusals.push_back({a.utime, a.request_id, a.status});
  std::set<std::tuple<int64_t, int, std::string>> tasks;
  for (const TaskStatusLine& t : log.task_status)
    if ((t.state == TaskState::kFailed || t.state == TaskState::kCanceled) &&
        tasks.insert({t.task_id, static_cast<int>(t.state), t.message}).second)
      r.task_failures.push_back(t);
  std::map<std::pair<std::string, int>, size_t> problem;  // (process, state) -> index
  for (const HeartbeatSample& h : log.heartbeats) {
    if (h.state != HeartbeatState::kWarn && h.state != HeartbeatState::kError) continue;
    const std::string process = h.instance.empty() ? h.process : h.process + "/" + h.instance;
    const auto key = std::make_pair(process, static_cast<int>(h.state));
    const auto it = problem.find(key);
    if (it == problem.end()) {
      problem[key] = r.heartbeat_problems.size();
      r.heartbeat_problems.push_back({process, h.state, h.utime, h.message, 1});
    } else {
      ++r.heartbeat_problems[it->second].count;
    }
  }
  for (const LoggedPath& d : log.drive_paths) r.drive_path_cancels += d.feasible ? 0 : 1;
  return r;
}

std::vector<Pose2> StandingPoses(const std::vector<StampedPose>& truth, int64_t min_duration_us, double max_motion) {
  std::vector<Pose2> out;
  size_t begin = 0;
  auto close_stop = [&](size_t end) {  // truth[begin .. end) stayed near truth[begin]
    if (end > begin && truth[end - 1].utime - truth[begin].utime >= min_duration_us) out.push_back(truth[begin].pose);
  };
  for (size_t i = 1; i <= truth.size(); ++i) {
    if (i < truth.size() && TranslationDistance(truth[i].pose, truth[begin].pose) < max_motion) continue;
    close_stop(i);
    begin = i;
  }
  return out;
}

MissionFigures EvaluateMission(const MissionInputs& in, const MissionEvaluationOptions& o) {
  MissionFigures f;
  const MissionReport* mission = in.mission ? &*in.mission : nullptr;
  f.have_mission = mission != nullptr;
  f.time = MissionTimes(in.log, mission);

  std::vector<mapper::Contour> contours;
  for (const auto& [id, c] : in.map.contours()) contours.push_back(c);
  const ContourFreeSpace space = MakeContourFreeSpace(contours, o.free_space);
  const KnownFreeSpace known(space, o.free_space);
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  auto grow = [&](const Eigen::Vector2d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  };
  for (const auto* world : {&in.initial_world, &in.final_world})
    for (const Segment& s : *world) grow(s.a), grow(s.b);
  for (const Segment& s : space.walls) grow(s.a), grow(s.b);
  if (!(lo.x() <= hi.x())) lo = hi = Eigen::Vector2d::Zero();
  const Eigen::Vector2d margin = Eigen::Vector2d::Constant(o.area_margin);
  lo -= margin;
  hi += margin;
  // A section far larger than a mine (a stray contour kilometres out) gets coarser cells, so
  // the grid stays within kMaxAreaCells; the cell used is in the figures.
  double cell = o.area_cell;
  while ((hi.x() - lo.x()) / cell * ((hi.y() - lo.y()) / cell) > kMaxAreaCells) cell *= 2.0;
  f.grid = MakeAreaGrid(in.final_world, [&](const Eigen::Vector2d& p) { return known.Contains(p); }, lo, hi, cell);
  f.area = MeasureArea(f.grid);

  f.map.deviation = mapper::ContourDeviation(in.map, in.final_world, o.deviation_step);
  f.map.contours = in.map.NumContours();
  f.map.segments = in.map.NumSegments();
  f.map.length_m = in.map.TotalLength();

  f.estimate = ComparePoses(in.log.estimates, in.log.truth, o.max_truth_gap_us);
  f.odometry = ComparePoses(AlignToTruthAtStart(in.log.odometry, in.log.truth, o.max_truth_gap_us), in.log.truth,
                            o.max_truth_gap_us);
  if (mission)
    f.cuts = MeasureCuts(mission->subtasks, in.initial_world, in.final_world, space.walls, o.cut, o.cut_tolerance);
  f.planning = MeasurePlanning(in.log.planner_paths, mission);
  f.refusals = MeasureRefusals(in.log, mission);
  if (!in.log.scan_stations.empty()) {
    f.stations = in.log.scan_stations;
    f.stations_source = "TASK_PLAN scan stations";
    f.log_stations = true;
  } else {
    f.stations = StandingPoses(in.log.truth, std::llround(o.standing_time * 1e6), o.standing_motion);
    f.stations_source = "where the vehicle stood for " + Fixed(o.standing_time, 1) + " s or more";
  }
  return f;
}

// ----------------------------------------------------------------------------------- JSON

namespace {

using nlohmann::json;

json ToJson(const Distribution& d) {
  return {{"count", d.count}, {"mean", d.mean}, {"median", d.median}, {"p95", d.p95}, {"max", d.max}};
}

json ToJson(const PoseErrorFigures& e) {
  return {{"compared", e.compared},
          {"unmatched", e.unmatched},
          {"mean_m", e.mean_m},
          {"rms_m", e.rms_m},
          {"max_m", e.max_m},
          {"mean_heading_deg", RadToDeg(e.mean_heading_rad)},
          {"max_heading_deg", RadToDeg(e.max_heading_rad)},
          {"worst_utime", e.worst_utime}};
}

json ToJson(const DepthFigures& d) {
  return {{"rays", d.rays}, {"hits", d.hits}, {"median_m", d.median}, {"min_m", d.min}, {"max_m", d.max}};
}

json Optional(const std::optional<double>& v) { return v ? json(*v) : json(nullptr); }

}  // namespace

std::string MissionFiguresToJson(const MissionInputs& in, const MissionFigures& f, const MissionEvaluationOptions& o) {
  const MissionRecord& log = in.log;
  json j;
  j["notes"] = in.notes;
  j["headline"] = HeadlineLines(in, f);
  j["inputs"] = {{"world", in.world_source}, {"map", in.map_source}, {"mission", f.have_mission}};
  j["log"] = {{"events", log.events},
              {"seconds", f.time.log_s},
              {"bad_messages", log.bad_messages},
              {"first_bad", log.first_bad},
              {"auth_refused", log.auth_refused},
              {"first_auth_refused", log.first_auth_refused},
              {"damage", log.damage},
              {"truth_poses", log.truth.size()},
              {"estimates", log.estimates.size()},
              {"odometry", log.odometry.size()},
              {"worlds", log.worlds.size()},
              {"planner_paths", log.planner_paths.size()},
              {"drive_paths", log.drive_paths.size()},
              {"task_status", log.task_status.size()},
              {"mission_status", log.mission_status.size()},
              {"heartbeats", log.heartbeats.size()}};
  j["time"] = {{"log_s", f.time.log_s},
               {"mission_s", Optional(f.time.mission_s)},
               {"exploration_s", Optional(f.time.exploration_s)},
               {"exploration_result", f.time.exploration_result},
               {"final_state", f.time.final_state},
               {"final_message", f.time.final_message},
               {"coordinator_s", in.mission ? json(in.mission->seconds) : json(nullptr)}};
  j["explored_area"] = {{"cell_m", f.area.cell_m},
                        {"true_free_m2", f.area.true_free_m2},
                        {"known_free_m2", f.area.known_free_m2},
                        {"explored_m2", f.area.explored_m2},
                        {"falsely_free_m2", f.area.falsely_free_m2},
                        {"explored_fraction", f.area.explored_fraction}};
  j["map_accuracy"] = {{"contours", f.map.contours},
                       {"segments", f.map.segments},
                       {"length_m", f.map.length_m},
                       {"deviation_mean_m", f.map.deviation.mean},
                       {"deviation_max_m", f.map.deviation.max},
                       {"samples", f.map.deviation.samples},
                       {"worst_point", {f.map.deviation.worst_point.x(), f.map.deviation.worst_point.y()}},
                       {"worst_contour", f.map.deviation.worst_contour},
                       {"sample_step_m", o.deviation_step}};
  j["pose_error"] = {{"estimate", ToJson(f.estimate)}, {"odometry", ToJson(f.odometry)}};
  json cuts = json::array();
  int flagged = 0;
  for (const CutFigures& c : f.cuts) {
    flagged += c.off_request ? 1 : 0;
    json x = {{"id", c.id},
              {"kind", c.kind},
              {"description", c.description},
              {"state", c.state},
              {"requested_m", c.requested_m},
              {"target", {c.target.x, c.target.y, c.target.theta}},
              {"truth", ToJson(c.truth)},
              {"map", ToJson(c.map)},
              {"off_request", c.off_request},
              {"map_off", c.map_off},
              {"note", c.note}};
    x["face"] = c.face ? json{c.face->a.x(), c.face->a.y(), c.face->b.x(), c.face->b.y()} : json(nullptr);
    cuts.push_back(x);
  }
  j["cuts"] = cuts;
  j["cuts_flagged"] = flagged;
  j["cut_tolerance_m"] = o.cut_tolerance;
  const PlanningFigures& p = f.planning;
  j["planning"] = {{"answers", p.answers},
                   {"searches", p.searches},
                   {"replanned", p.replanned},
                   {"refused", p.refused},
                   {"unparsed", p.unparsed},
                   {"unparsed_examples", p.unparsed_examples},
                   {"search_ms", ToJson(p.search_ms)}};
  j["planning"]["coordinator"] = p.have_mission ? json{{"drives", p.drives},
                                                       {"drives_planned_ahead", p.drives_planned_ahead},
                                                       {"waits_s", ToJson(p.waits_s)},
                                                       {"waits_zero", p.waits_zero}}
                                                : json(nullptr);
  const RefusalFigures& r = f.refusals;
  json path_refusals = json::array(), task_failures = json::array(), heartbeat = json::array();
  for (const PathRefusal& x : r.path_refusals)
    path_refusals.push_back({{"utime", x.utime}, {"request_id", x.request_id}, {"status", x.status}});
  for (const TaskStatusLine& x : r.task_failures)
    task_failures.push_back(
        {{"utime", x.utime}, {"task_id", x.task_id}, {"state", TaskStateName(x.state)}, {"message", x.message}});
  for (const HeartbeatProblem& x : r.heartbeat_problems)
    heartbeat.push_back({{"process", x.process},
                         {"state", ToString(x.state)},
                         {"first_utime", x.first_utime},
                         {"first_message", x.first_message},
                         {"count", x.count}});
  j["retried_or_refused"] = {{"events", r.events},
                             {"retries", r.retries},
                             {"replans", r.replans},
                             {"resends", r.resends},
                             {"pauses_for_lost_processes", r.pauses},
                             {"path_refusals", path_refusals},
                             {"task_failures", task_failures},
                             {"heartbeat_problems", heartbeat},
                             {"drive_path_cancels", r.drive_path_cancels}};
  json stations = json::array();
  for (const Pose2& s : f.stations) stations.push_back({s.x, s.y, s.theta});
  j["stations"] = {{"source", f.stations_source}, {"poses", stations}};
  j["mission"] = in.mission ? json{{"id", in.mission->mission_id},
                                   {"state", in.mission->state},
                                   {"message", in.mission->message},
                                   {"stations_visited", in.mission->stations_visited},
                                   {"stations_failed", in.mission->stations_failed}}
                            : json(nullptr);
  return j.dump(2) + "\n";
}

// ------------------------------------------------------------------------------- Markdown

std::vector<std::string> HeadlineLines(const MissionInputs& in, const MissionFigures& f) {
  std::vector<std::string> out;
  std::string line = "explored " + Fixed(f.area.explored_m2, 0) + " m² of " + Fixed(f.area.true_free_m2, 0) +
                     " m² free (" + Fixed(100.0 * f.area.explored_fraction, 1) + " %)";
  if (f.time.exploration_s) line += " in " + Fixed(*f.time.exploration_s, 0) + " s";
  if (f.time.mission_s) line += "; mission " + f.time.final_state + " after " + Fixed(*f.time.mission_s, 0) + " s";
  else if (!f.time.final_state.empty()) line += "; mission " + f.time.final_state;
  out.push_back(line);
  out.push_back("map: " + std::to_string(f.map.contours) + " contours, " + Fixed(f.map.length_m, 0) +
                " m; deviation from the true walls mean " + Fixed(f.map.deviation.mean, 3) + " m, max " +
                Fixed(f.map.deviation.max, 2) + " m");
  if (f.estimate.compared > 0 || f.odometry.compared > 0)
    out.push_back("pose error: estimate RMS " + Fixed(f.estimate.rms_m, 3) + " m, max " + Fixed(f.estimate.max_m, 3) +
                  " m, heading max " + Fixed(RadToDeg(f.estimate.max_heading_rad), 2) + "°; odometry max " +
                  Fixed(f.odometry.max_m, 2) + " m, " + Fixed(RadToDeg(f.odometry.max_heading_rad), 1) + "°");
  if (!f.cuts.empty()) {
    std::string cuts = "cuts:";
    for (const CutFigures& c : f.cuts)
      cuts += " " + c.kind + " " + Fixed(c.truth.median, 2) + " m of " + Fixed(c.requested_m, 2) + " m" +
              (c.off_request ? " (OFF)" : "") + ";";
    cuts.pop_back();
    out.push_back(cuts);
  }
  std::string planning = "planning: " + std::to_string(f.planning.searches) + " searches";
  if (f.planning.searches > 0)
    planning += ", median " + Fixed(f.planning.search_ms.median, 1) + " ms, max " + Fixed(f.planning.search_ms.max, 1) +
                " ms";
  if (f.planning.have_mission)
    planning += "; " + std::to_string(f.planning.drives_planned_ahead) + " of " + std::to_string(f.planning.drives) +
                " drives planned ahead";
  out.push_back(planning);
  out.push_back("retried or refused: " + std::to_string(f.refusals.events.size()) + " coordinator events, " +
                std::to_string(f.refusals.path_refusals.size()) + " paths refused, " +
                std::to_string(f.refusals.task_failures.size()) + " tasks failed or canceled, " +
                std::to_string(f.refusals.heartbeat_problems.size()) + " heartbeat warnings or errors");
  for (const std::string& n : in.notes) out.push_back(n);
  return out;
}

namespace {

// A Markdown table cell: no pipes or line breaks.
std::string Cell(std::string s) {
  for (char& c : s)
    if (c == '|' || c == '\n' || c == '\r') c = ' ';
  return s;
}

std::string Seconds(const std::optional<double>& s) { return s ? Fixed(*s, 1) + " s" : "-"; }

}  // namespace

std::string MissionReportMarkdown(const MissionInputs& in, const MissionFigures& f, const MissionEvaluationOptions& o) {
  std::ostringstream md;
  md << "# Mission report\n\n";
  for (const std::string& l : HeadlineLines(in, f)) md << "- " << Cell(l) << "\n";
  md << "\n## Explored area and time\n\n| figure | value |\n|---|---|\n"
     << "| true free area of the section | " << Fixed(f.area.true_free_m2, 1) << " m² |\n"
     << "| area the final map shows free | " << Fixed(f.area.known_free_m2, 1) << " m² |\n"
     << "| explored (shown free and truly free) | " << Fixed(f.area.explored_m2, 1) << " m² ("
     << Fixed(100.0 * f.area.explored_fraction, 1) << " %) |\n"
     << "| shown free but not free | " << Fixed(f.area.falsely_free_m2, 2) << " m² |\n"
     << "| grid cell | " << Fixed(f.area.cell_m, 2) << " m |\n"
     << "| exploration | " << Seconds(f.time.exploration_s)
     << (f.time.exploration_result.empty() ? "" : " (" + f.time.exploration_result + ")") << " |\n"
     << "| mission | " << Seconds(f.time.mission_s) << " (" << (f.time.final_state.empty() ? "no MISSION_STATUS" : f.time.final_state)
     << ") |\n"
     << "| log | " << Fixed(f.time.log_s, 1) << " s |\n";
  if (in.mission)
    md << "| coordinator | " << Fixed(in.mission->seconds, 1) << " s, " << in.mission->stations_visited
       << " stations visited, " << in.mission->stations_failed << " not reached |\n";

  md << "\n## Map accuracy (final contour map against the final true walls)\n\n| figure | value |\n|---|---|\n"
     << "| contours | " << f.map.contours << " (" << f.map.segments << " segments, " << Fixed(f.map.length_m, 1)
     << " m) |\n"
     << "| deviation mean | " << Fixed(f.map.deviation.mean, 3) << " m |\n"
     << "| deviation max | " << Fixed(f.map.deviation.max, 3) << " m at (" << Fixed(f.map.deviation.worst_point.x(), 2)
     << ", " << Fixed(f.map.deviation.worst_point.y(), 2) << ") |\n";

  md << "\n## Pose error along the drive (against SIM_TRUTH at each pose's utime)\n\n"
     << "| track | poses | mean | RMS | max | max heading |\n|---|---|---|---|---|---|\n";
  auto pose_row = [&](const char* name, const PoseErrorFigures& e) {
    md << "| " << name << " | " << e.compared << (e.unmatched ? " (+" + std::to_string(e.unmatched) + " without truth)" : "")
       << " | " << Fixed(e.mean_m, 3) << " m | " << Fixed(e.rms_m, 3) << " m | " << Fixed(e.max_m, 3) << " m | "
       << Fixed(RadToDeg(e.max_heading_rad), 2) << "° |\n";
  };
  pose_row("POSE (the fleet's estimate)", f.estimate);
  pose_row("ODOMETRY (dead reckoning, aligned at its start)", f.odometry);

  md << "\n## Cuts (depth along the direction of advance, rays across " << Fixed(100 * o.cut.inner_from, 0) << "-"
     << Fixed(100 * o.cut.inner_to, 0) << " % of the face)\n\n";
  if (!in.mission) {
    md << "No mission report (--mission): no per-cut section.\n";
  } else if (f.cuts.empty()) {
    md << "No BOX_CUT or SLAB_CUT subtask in the mission.\n";
  } else {
    md << "| subtask | requested | true depth median (min .. max) | map depth median | state | flag |\n"
       << "|---|---|---|---|---|---|\n";
    for (const CutFigures& c : f.cuts)
      md << "| " << c.id << " " << c.kind << " | " << Fixed(c.requested_m, 2) << " m | " << Fixed(c.truth.median, 3)
         << " m (" << Fixed(c.truth.min, 3) << " .. " << Fixed(c.truth.max, 3) << "), " << c.truth.hits << "/"
         << c.truth.rays << " rays | " << Fixed(c.map.median, 3) << " m" << (c.map_off ? " (map off)" : "") << " | "
         << Cell(c.state) << " | "
         << (c.off_request ? "OFF by more than " + Fixed(o.cut_tolerance, 2) + " m" : "ok")
         << (c.note.empty() ? "" : "; " + Cell(c.note)) << " |\n";
  }

  const PlanningFigures& p = f.planning;
  md << "\n## Planning\n\n| figure | value |\n|---|---|\n"
     << "| path planner searches | " << p.searches << " (" << p.replanned << " replans), " << p.refused << " refused, "
     << p.unparsed << " status lines not understood |\n"
     << "| search time | "
     << (p.search_ms.count == 0 ? std::string("-")
                                : "median " + Fixed(p.search_ms.median, 1) + " ms, p95 " + Fixed(p.search_ms.p95, 1) +
                                      " ms, max " + Fixed(p.search_ms.max, 1) + " ms")
     << " |\n";
  if (p.have_mission)
    md << "| effective planning wait (coordinator) | median " << Fixed(p.waits_s.median, 2) << " s, max "
       << Fixed(p.waits_s.max, 2) << " s over " << p.waits_s.count << " drives; " << p.waits_zero << " waited 0 s |\n"
       << "| drives using a path planned ahead | " << p.drives_planned_ahead << " of " << p.drives << " |\n";

  const RefusalFigures& r = f.refusals;
  md << "\n## Retried or refused\n\n";
  if (in.mission)
    md << "Coordinator: " << r.retries << " retries, " << r.replans << " replans, " << r.resends << " resends, "
       << r.pauses << " pauses for lost processes; " << r.drive_path_cancels << " paths canceled on DRIVE_PATH.\n\n";
  auto list = [&](const std::string& title, const std::vector<std::string>& lines) {
    md << "**" << title << "** (" << lines.size() << ")" << (lines.empty() ? "\n\n" : ":\n\n");
    for (const std::string& l : lines) md << "- " << l << "\n";
    if (!lines.empty()) md << "\n";
  };
  list("Coordinator events", r.events);
  std::vector<std::string> lines;
  for (const PathRefusal& x : r.path_refusals) lines.push_back("request " + std::to_string(x.request_id) + ": " + x.status);
  list("Paths refused by the planner", lines);
  lines.clear();
  for (const TaskStatusLine& x : r.task_failures)
    lines.push_back("task " + std::to_string(x.task_id) + " " + TaskStateName(x.state) + ": " + x.message);
  list("Tasks failed or canceled", lines);
  lines.clear();
  for (const HeartbeatProblem& x : r.heartbeat_problems)
    lines.push_back(x.process + " " + ToString(x.state) + " (" + std::to_string(x.count) + " heartbeats), first: " +
                    x.first_message);
  list("Processes whose heartbeat went WARN or ERROR", lines);

  md << "## Inputs\n\n- world: " << in.world_source << "\n- map: " << in.map_source << "\n- log: " << in.log.events
     << " events, " << in.log.bad_messages << " messages not decoded"
     << (in.log.first_bad.empty() ? "" : " (first: " + Cell(in.log.first_bad) + ")") << "\n";
  if (in.log.auth_refused > 0)
    md << "- refused by authentication (the fleet's key): " << in.log.auth_refused
       << " messages on signed channels, not used (first: " << Cell(in.log.first_auth_refused) << ")\n";
  if (!in.log.damage.empty()) md << "- log damaged: " << in.log.damage << " (what came before is used)\n";
  md << "- stations: " << f.stations.size() << " (" << f.stations_source << ")\n";
  return md.str();
}

}  // namespace minenav
