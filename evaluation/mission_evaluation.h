#pragma once
// The report of a finished mission (issue 15, the main job): from what the mission left
// behind (its log decoded into a MissionRecord, the true worlds, the final contour map, the
// coordinator's report) every figure the report shows, as JSON for tests and CI and as a
// short Markdown report for people. evaluation/README.md ("Mission report") says what each
// figure means and how it is computed; `log_tool mission-report` (logger/) is the command.
// Plain C++: no LCM, clock or I/O. May see the simulator's world: this is evaluation.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "evaluation/map_evaluation.h"
#include "evaluation/mission_figures.h"
#include "evaluation/mission_record.h"
#include "mapper/contour_map.h"
#include "planner/contour_free_space.h"

namespace minenav {

class OptionScope;

struct MissionEvaluationOptions {
  double area_cell = 0.2;            // m, cell of the explored-area grid (doubled until the grid has at most 4e6 cells)
  double area_margin = 1.0;          // m, grid margin around the true world and the map
  double deviation_step = 0.05;      // m, contour sampling step of the map accuracy
  int64_t max_truth_gap_us = 500000; // us: a pose is compared with the truth interpolated between readings at most twice this apart
  double standing_time = 2.0;        // s: where the truth stood still this long counts as a station (when no TASK_PLAN names them)
  double standing_motion = 0.05;     // m: ... moving less than this
  CutDepthOptions cut;               // the rays across each cut face
  double cut_tolerance = 0.05;       // m: a cut deeper or shallower than requested by more is flagged
  FreeSpaceOptions free_space;       // the map's known free space (planner/contour_free_space.h)
};
// Every field (cut.*, free_space.* nested), with unit, range and meaning.
void DeclareOptions(OptionScope scope, MissionEvaluationOptions& o);

struct MissionInputs {
  MissionRecord log;
  std::vector<Segment> initial_world;  // the true world at the start
  std::vector<Segment> final_world;    // after the cuts (the last SIM_WORLD; the initial one without)
  std::string world_source;            // one line: where the worlds came from
  mapper::ContourMap map;              // the final live contour map
  std::string map_source;
  std::optional<MissionReport> mission;  // the coordinator's report; no per-cut section without it
  std::vector<std::string> notes;      // lines the caller adds (e.g. the speed factor of the run)
};

struct TimeFigures {
  double log_s = 0.0;                  // first to last event of the log
  std::optional<double> mission_s;     // MISSION_STATUS: first WAITING/RUNNING to the first DONE/FAILED/ABORTED
  std::optional<double> exploration_s; // the exploration leaf ("explore ...") from RUNNING to SUCCESS/FAILURE
  std::string exploration_result;      // "success", "failure", "unfinished" or "" (no exploration leaf)
  std::string final_state;             // the last MISSION_STATUS state ("" when none)
  std::string final_message;
};
// `report`, the coordinator's own (--report-out), when there is one: its end state wins when the
// log has none (the logger may stop before the coordinator's last MISSION_STATUS is heard).
TimeFigures MissionTimes(const MissionRecord& log, const MissionReport* report = nullptr);

struct MapFigures {
  mapper::MapDeviation deviation;  // contours against the final true walls
  int contours = 0;
  int segments = 0;
  double length_m = 0.0;
};

struct CutFigures {
  int64_t id = 0;
  std::string kind, description, state;
  double requested_m = 0.0;
  Pose2 target;
  std::optional<Segment> face;
  DepthFigures truth;  // final true world against the initial one
  DepthFigures map;    // final contour map against the initial true world
  bool off_request = false;  // |truth median - requested| > cut_tolerance, or no ray measured
  bool map_off = false;      // |map median - truth median| > cut_tolerance, or no ray measured
  std::string note;          // why it was not measured, when it was not
};
// BOX_CUT and SLAB_CUT subtasks measured with rays along target.theta (the direction of advance).
std::vector<CutFigures> MeasureCuts(const std::vector<MissionSubtask>& subtasks, const std::vector<Segment>& initial,
                                    const std::vector<Segment>& final_world, const std::vector<Segment>& map_walls,
                                    const CutDepthOptions& options, double tolerance);

struct PlanningFigures {
  int answers = 0;    // distinct PATH answers (request id and status line)
  int searches = 0;   // feasible answers whose status parsed
  int replanned = 0;  // of those, replans
  int refused = 0;    // feasible = false
  int unparsed = 0;   // feasible answers whose status line did not parse
  std::vector<std::string> unparsed_examples;  // the first few
  Distribution search_ms;
  // From the coordinator's report (have_mission false without it).
  bool have_mission = false;
  int drives = 0, drives_planned_ahead = 0;
  Distribution waits_s;  // effective planning waits
  int waits_zero = 0;    // of them, exactly 0 s (a path planned ahead)
};
PlanningFigures MeasurePlanning(const std::vector<LoggedPath>& answers, const MissionReport* mission);

struct PathRefusal {
  int64_t utime = 0, request_id = 0;
  std::string status;
};
struct HeartbeatProblem {
  std::string process;
  HeartbeatState state = HeartbeatState::kWarn;
  int64_t first_utime = 0;
  std::string first_message;
  int count = 0;  // heartbeats in that state
};
struct RefusalFigures {
  std::vector<std::string> events;                   // the coordinator's (retried, refused, lost)
  int retries = 0, replans = 0, resends = 0, pauses = 0;  // the coordinator's counters
  std::vector<PathRefusal> path_refusals;            // PATH feasible = false, each (request, status) once
  std::vector<TaskStatusLine> task_failures;         // TASK_STATUS FAILED / CANCELED, each (task, state, message) once
  std::vector<HeartbeatProblem> heartbeat_problems;  // per process and state (WARN, ERROR), by first time
  int drive_path_cancels = 0;                        // DRIVE_PATH with feasible = false (the coordinator cancels a path)
};
RefusalFigures MeasureRefusals(const MissionRecord& log, const MissionReport* mission);

// Where the truth stood still for at least min_duration_us, moving less than max_motion m:
// one pose per stop (where it began).
std::vector<Pose2> StandingPoses(const std::vector<StampedPose>& truth, int64_t min_duration_us, double max_motion);

struct MissionFigures {
  TimeFigures time;
  AreaGrid grid;  // the explored-area grid (also drawn)
  AreaFigures area;
  MapFigures map;
  PoseErrorFigures estimate;  // POSE against SIM_TRUTH
  PoseErrorFigures odometry;  // ODOMETRY (aligned at its start) against SIM_TRUTH
  std::vector<CutFigures> cuts;
  PlanningFigures planning;
  RefusalFigures refusals;
  std::vector<Pose2> stations;
  std::string stations_source;  // "TASK_PLAN scan stations" or "where the vehicle stood ..."
  bool log_stations = false;    // the stations are TASK_PLAN's
  bool have_mission = false;
};

MissionFigures EvaluateMission(const MissionInputs& in, const MissionEvaluationOptions& options = {});

// Every figure, as JSON (the keys are listed in evaluation/README.md).
std::string MissionFiguresToJson(const MissionInputs& in, const MissionFigures& f, const MissionEvaluationOptions& o);
// The short report for people: a few tables.
std::string MissionReportMarkdown(const MissionInputs& in, const MissionFigures& f, const MissionEvaluationOptions& o);
// The headline figures, one line each (the report's first lines and the picture's notes).
std::vector<std::string> HeadlineLines(const MissionInputs& in, const MissionFigures& f);

}  // namespace minenav
