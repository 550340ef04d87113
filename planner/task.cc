#include "planner/task.h"

namespace minenav {

const char* ToString(TaskKind k) {
  switch (k) {
    case TaskKind::kMove: return "move";
    case TaskKind::kBoxCut: return "box_cut";
    case TaskKind::kSlabCut: return "slab_cut";
    case TaskKind::kBackOut: return "back_out";
    case TaskKind::kScanStation: return "scan_station";
    case TaskKind::kTurn: return "turn";
    case TaskKind::kWait: return "wait";
  }
  return "unknown";
}

const char* ToString(TaskPlanStatus s) {
  switch (s) {
    case TaskPlanStatus::kOk: return "ok";
    case TaskPlanStatus::kComplete: return "complete";
    case TaskPlanStatus::kFailed: return "failed";
  }
  return "unknown";
}

const char* ToString(TaskRequestKind k) {
  switch (k) {
    case TaskRequestKind::kSurveyNext: return "survey_next";
    case TaskRequestKind::kAdvance: return "advance";
  }
  return "unknown";
}

}  // namespace minenav
