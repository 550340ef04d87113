#pragma once
// Subtasks of a mission (thesis 6.2.1, Figure 40) as plain values: what the task planner
// plans and the coordinator executes. Their messages are task_t / task_plan_t /
// task_request_t (lcmtypes/); planner/task_message.h converts. Poses in the map frame.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "common/pose2.h"

namespace minenav {

// The values are task_t's kind constants.
enum class TaskKind : int8_t {
  kMove = 0,         // drive to target (into position, reposition)
  kBoxCut = 1,       // sump-shear cycles into the face until depth (6.4.1)
  kSlabCut = 2,      // the rest of the entry's width beside the box cut
  kBackOut = 3,      // drive back from the face (for the roof bolter)
  kScanStation = 4,  // drive to a scan station of a survey and stand for the ladar
  kTurn = 5,         // turn (in place or by a maneuver) to target
  kWait = 6,         // stand still
};

// The state the cutter's appendages must be in for a task (task_t's APPENDAGES_ constants).
enum class Appendages : int8_t {
  kAny = 0,
  kStowed = 1,   // boom up, drum off: the only state the miner may tram in (6.2.1)
  kCutting = 2,  // the cutter owns them
};

struct Task {
  int64_t id = 0;
  TaskKind kind = TaskKind::kMove;
  Pose2 target;                // where the task drives to, or cuts from (squared up)
  double depth = 0.0;          // m, cuts
  double width = 0.0;          // m, cuts
  int64_t depends_on = -1;     // task id that must finish first, -1 none
  std::string description;     // one line
  std::optional<Segment> face; // cuts: the face line to cut
  double clearance = 0.0;      // m, driving tasks
  bool allow_reverse = true;   // driving tasks
  Appendages appendages = Appendages::kAny;
};

enum class TaskPlanStatus : int8_t { kOk = 0, kComplete = 1, kFailed = 2 };

struct TaskPlan {
  int64_t plan_id = 0;
  int64_t request_id = 0;
  std::string mission_id;
  TaskPlanStatus status = TaskPlanStatus::kFailed;
  std::string reason;
  std::vector<Task> tasks;
};

enum class TaskRequestKind : int8_t { kSurveyNext = 0, kAdvance = 1 };

struct TaskRequest {
  int64_t request_id = 0;
  std::string mission_id;
  TaskRequestKind kind = TaskRequestKind::kSurveyNext;
  Pose2 pose;          // the vehicle's estimate when asked
  Pose2 face;          // advance: a point in front of the face, theta = direction of advance
  double depth = 0.0;  // m, advance
  double clearance = 0.0;
};

// True for the kinds that drive the vehicle to `target` on a planned path.
inline bool IsDrivingTask(TaskKind k) {
  return k == TaskKind::kMove || k == TaskKind::kBackOut || k == TaskKind::kScanStation || k == TaskKind::kTurn;
}
inline bool IsCutTask(TaskKind k) { return k == TaskKind::kBoxCut || k == TaskKind::kSlabCut; }

// "move", "box_cut", ... (logs, the mission's task tree).
const char* ToString(TaskKind k);
const char* ToString(TaskPlanStatus s);
const char* ToString(TaskRequestKind k);

}  // namespace minenav
