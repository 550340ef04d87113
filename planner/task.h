#pragma once
// The task planner's plain types (thesis 6.2.1): a plan is a sequence of subtasks, each
// "parameterized by geometric constraints on the motion of the miner, goal points ... and
// ordering constraints on the appendage operations". They mirror lcmtypes/task_t.lcm and
// task_plan_t.lcm one to one (the node converts, planner/task_plan_message.h); the
// algorithms (advance_planner.h, survey_planner.h) know no LCM.
// The map the task planner works on is planner/task_map.h.

#include <cstdint>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "common/pose2.h"

namespace minenav {

// task_t's kind constants.
enum class TaskKind : int8_t {
  kMove = 0,
  kBoxCut = 1,
  kSlabCut = 2,
  kBackOut = 3,
  kScanStation = 4,
  kTurn = 5,
  kWait = 6,
};
// task_t's APPENDAGES_ constants: the state the cutter appendages must be in before the task
// starts and while it runs.
enum class Appendages : int8_t {
  kAny = 0,
  kStowed = 1,   // boom up, drum off: the only state to tram in
  kCutting = 2,  // the cutter owns them
};
// task_plan_t's status constants.
enum class PlanStatus : int8_t {
  kOk = 0,        // tasks to do
  kComplete = 1,  // nothing left to do (a survey: no reachable frontier remains)
  kFailed = 2,    // the request cannot be planned; the reason says why
};

// "move", "box_cut", "slab_cut", "back_out", "scan_station", "turn", "wait".
std::string ToString(TaskKind kind);
// "ok", "complete", "failed".
std::string ToString(PlanStatus status);
// "any", "stowed", "cutting".
std::string ToString(Appendages appendages);

// A number as the plans' one-line reasons write it: fixed, `digits` decimals.
std::string FixedNumber(double v, int digits = 2);
// "(x, y, theta)" with two decimals: a pose in a reason.
std::string PoseText(const Pose2& pose);

struct Task {
  int64_t id = 0;
  TaskKind kind = TaskKind::kMove;
  Pose2 target;             // m, m, rad, map frame: where the task drives to, or cuts from (squared up)
  double depth = 0.0;       // m, cut depth into the face (cuts)
  double width = 0.0;       // m, new width the cut takes out of the face (cuts)
  int64_t depends_on = -1;  // id of the task that must finish first, -1 for none
  std::string description;  // one line for people
  Segment face;             // m, the face as the drum meets it (cuts), free space on its left; zero otherwise
  double clearance = 0.0;   // m, least distance from the vehicle polygon to the walls on the way (driving tasks)
  bool allow_reverse = false;
  Appendages appendages = Appendages::kAny;
};

// True for the kinds that drive the vehicle to `target` on a planned path.
inline bool IsDrivingTask(TaskKind k) {
  return k == TaskKind::kMove || k == TaskKind::kBackOut || k == TaskKind::kScanStation || k == TaskKind::kTurn;
}
inline bool IsCutTask(TaskKind k) { return k == TaskKind::kBoxCut || k == TaskKind::kSlabCut; }

struct TaskPlan {
  PlanStatus status = PlanStatus::kFailed;
  std::string reason;  // one line: what the plan is, or why there is none
  std::vector<Task> tasks;
};

// A request for subtasks (task_request_t): the next scan station, or advancing an entry.
enum class TaskRequestKind : int8_t { kSurveyNext = 0, kAdvance = 1 };
struct TaskRequest {
  int64_t utime = 0;
  int64_t request_id = 0;
  std::string mission_id;
  TaskRequestKind kind = TaskRequestKind::kSurveyNext;
  Pose2 pose;              // the vehicle (map frame)
  Pose2 face;              // ADVANCE: a point in front of the face and the direction of advance
  double depth = 0.0;      // m, ADVANCE
  double clearance = 0.0;  // m
};
// "survey_next", "advance".
std::string ToString(TaskRequestKind kind);

}  // namespace minenav
