#include "planner/task_message.h"

#include <cmath>
#include <string>

#include "common/file_io.h"
#include "common/node/conversions.h"

namespace minenav {
namespace {

void CheckFinite(double v, const std::string& what) {
  if (!std::isfinite(v)) throw InputError(what + " is not finite");
}

void CheckNonNegative(double v, const std::string& what) {
  CheckFinite(v, what);
  if (v < 0.0) throw InputError(what + " is negative (" + std::to_string(v) + ")");
}

line_segment_t ToLcm(const std::optional<Segment>& s) {
  line_segment_t m{};
  if (s) {
    m.x1 = s->a.x();
    m.y1 = s->a.y();
    m.x2 = s->b.x();
    m.y2 = s->b.y();
  }
  return m;
}

std::optional<Segment> FaceFromLcm(const line_segment_t& m, const std::string& what) {
  for (const double v : {m.x1, m.y1, m.x2, m.y2}) CheckFinite(v, what);
  if (m.x1 == 0.0 && m.y1 == 0.0 && m.x2 == 0.0 && m.y2 == 0.0) return std::nullopt;
  return Segment(m.x1, m.y1, m.x2, m.y2);
}

}  // namespace

task_t ToLcm(const Task& t) {
  task_t m{};
  m.task_id = t.id;
  m.kind = static_cast<int8_t>(t.kind);
  m.target = ToLcm(t.target);
  m.depth = t.depth;
  m.width = t.width;
  m.depends_on = t.depends_on;
  m.description = t.description;
  m.face = ToLcm(t.face);
  m.clearance = t.clearance;
  m.allow_reverse = t.allow_reverse;
  m.appendages = static_cast<int8_t>(t.appendages);
  return m;
}

Task FromLcm(const task_t& m) {
  const std::string what = "task " + std::to_string(m.task_id);
  if (m.kind < task_t::MOVE || m.kind > task_t::WAIT)
    throw InputError(what + ": unknown kind " + std::to_string(m.kind));
  if (m.appendages < task_t::APPENDAGES_ANY || m.appendages > task_t::APPENDAGES_CUTTING)
    throw InputError(what + ": unknown appendages state " + std::to_string(m.appendages));
  Task t;
  t.id = m.task_id;
  t.kind = static_cast<TaskKind>(m.kind);
  t.target = FromLcm(m.target);
  CheckNonNegative(m.depth, what + " depth");
  CheckNonNegative(m.width, what + " width");
  CheckNonNegative(m.clearance, what + " clearance");
  t.depth = m.depth;
  t.width = m.width;
  t.depends_on = m.depends_on;
  t.description = m.description;
  t.face = FaceFromLcm(m.face, what + " face");
  if (IsCutTask(t.kind) && (t.depth <= 0.0 || !t.face || t.face->length() <= 0.0))
    throw InputError(what + ": a cut needs a depth > 0 and a face line");
  t.clearance = m.clearance;
  t.allow_reverse = m.allow_reverse;
  t.appendages = static_cast<Appendages>(m.appendages);
  return t;
}

task_plan_t ToLcm(const TaskPlan& p, int64_t utime) {
  task_plan_t m{};
  m.utime = utime;
  m.plan_id = p.plan_id;
  m.request_id = p.request_id;
  m.mission_id = p.mission_id;
  m.status = static_cast<int8_t>(p.status);
  m.reason = p.reason;
  m.num_tasks = static_cast<int32_t>(p.tasks.size());
  for (const Task& t : p.tasks) m.tasks.push_back(ToLcm(t));
  return m;
}

TaskPlan FromLcm(const task_plan_t& m) {
  if (m.status < task_plan_t::OK || m.status > task_plan_t::FAILED)
    throw InputError("task plan " + std::to_string(m.plan_id) + ": unknown status " + std::to_string(m.status));
  if (m.num_tasks < 0 || static_cast<size_t>(m.num_tasks) != m.tasks.size())
    throw InputError("task plan " + std::to_string(m.plan_id) + ": num_tasks does not match the tasks");
  TaskPlan p;
  p.plan_id = m.plan_id;
  p.request_id = m.request_id;
  p.mission_id = m.mission_id;
  p.status = static_cast<TaskPlanStatus>(m.status);
  p.reason = m.reason;
  for (const task_t& t : m.tasks) p.tasks.push_back(FromLcm(t));
  if (p.status == TaskPlanStatus::kOk && p.tasks.empty())
    throw InputError("task plan " + std::to_string(m.plan_id) + ": status ok without tasks");
  return p;
}

task_request_t ToLcm(const TaskRequest& r, int64_t utime) {
  task_request_t m{};
  m.utime = utime;
  m.request_id = r.request_id;
  m.mission_id = r.mission_id;
  m.kind = static_cast<int8_t>(r.kind);
  m.pose = ToLcm(r.pose);
  m.face = ToLcm(r.face);
  m.depth = r.depth;
  m.clearance = r.clearance;
  return m;
}

TaskRequest FromLcm(const task_request_t& m) {
  const std::string what = "task request " + std::to_string(m.request_id);
  if (m.kind < task_request_t::SURVEY_NEXT || m.kind > task_request_t::ADVANCE)
    throw InputError(what + ": unknown kind " + std::to_string(m.kind));
  TaskRequest r;
  r.request_id = m.request_id;
  r.mission_id = m.mission_id;
  r.kind = static_cast<TaskRequestKind>(m.kind);
  r.pose = FromLcm(m.pose);
  r.face = FromLcm(m.face);
  CheckNonNegative(m.depth, what + " depth");
  CheckNonNegative(m.clearance, what + " clearance");
  if (r.kind == TaskRequestKind::kAdvance && m.depth <= 0.0) throw InputError(what + ": advance needs a depth > 0");
  r.depth = m.depth;
  r.clearance = m.clearance;
  return r;
}

}  // namespace minenav
