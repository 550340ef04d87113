#include "planner/task.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

namespace minenav {

std::string ToString(TaskKind kind) {
  switch (kind) {
    case TaskKind::kMove:
      return "move";
    case TaskKind::kBoxCut:
      return "box_cut";
    case TaskKind::kSlabCut:
      return "slab_cut";
    case TaskKind::kBackOut:
      return "back_out";
    case TaskKind::kScanStation:
      return "scan_station";
    case TaskKind::kTurn:
      return "turn";
    case TaskKind::kWait:
      return "wait";
  }
  return "unknown";
}

std::string ToString(PlanStatus status) {
  switch (status) {
    case PlanStatus::kOk:
      return "ok";
    case PlanStatus::kComplete:
      return "complete";
    case PlanStatus::kFailed:
      return "failed";
  }
  return "unknown";
}

std::string ToString(Appendages appendages) {
  switch (appendages) {
    case Appendages::kAny:
      return "any";
    case Appendages::kStowed:
      return "stowed";
    case Appendages::kCutting:
      return "cutting";
  }
  return "unknown";
}

std::string FixedNumber(double v, int digits) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(digits);
  os << v;
  return os.str();
}

std::string PoseText(const Pose2& p) {
  return "(" + FixedNumber(p.x) + ", " + FixedNumber(p.y) + ", " + FixedNumber(p.theta) + ")";
}

std::string ToString(TaskRequestKind kind) { return kind == TaskRequestKind::kAdvance ? "advance" : "survey_next"; }

}  // namespace minenav
