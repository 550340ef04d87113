#include "planner/task_plan_message.h"

#include <cmath>

#include "common/file_io.h"
#include "common/node/conversions.h"

namespace minenav {
namespace {

bool Finite(const pose2d_t& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta); }

}  // namespace

task_t TaskToLcm(const Task& t) {
  task_t m{};
  m.task_id = t.id;
  m.kind = static_cast<int8_t>(t.kind);
  m.target = ToLcm(t.target);
  m.depth = t.depth;
  m.width = t.width;
  m.depends_on = t.depends_on;
  m.description = t.description;
  m.face.x1 = t.face.a.x();
  m.face.y1 = t.face.a.y();
  m.face.x2 = t.face.b.x();
  m.face.y2 = t.face.b.y();
  m.clearance = t.clearance;
  m.allow_reverse = t.allow_reverse;
  m.appendages = static_cast<int8_t>(t.appendages);
  return m;
}

Task TaskFromLcm(const task_t& m) {
  const std::string where = "task " + std::to_string(m.task_id) + ": ";
  if (m.kind < task_t::MOVE || m.kind > task_t::WAIT)
    throw InputError(where + "unknown kind " + std::to_string(m.kind));
  if (m.appendages < task_t::APPENDAGES_ANY || m.appendages > task_t::APPENDAGES_CUTTING)
    throw InputError(where + "unknown appendages " + std::to_string(m.appendages));
  if (!Finite(m.target)) throw InputError(where + "target is not finite");
  if (!std::isfinite(m.depth) || m.depth < 0.0) throw InputError(where + "depth is not a finite value >= 0");
  if (!std::isfinite(m.width) || m.width < 0.0) throw InputError(where + "width is not a finite value >= 0");
  if (!std::isfinite(m.clearance) || m.clearance < 0.0)
    throw InputError(where + "clearance is not a finite value >= 0");
  if (!std::isfinite(m.face.x1) || !std::isfinite(m.face.y1) || !std::isfinite(m.face.x2) || !std::isfinite(m.face.y2))
    throw InputError(where + "face is not finite");
  Task t;
  t.id = m.task_id;
  t.kind = static_cast<TaskKind>(m.kind);
  t.target = FromLcm(m.target);
  t.depth = m.depth;
  t.width = m.width;
  t.depends_on = m.depends_on;
  t.description = m.description;
  t.face = Segment(m.face.x1, m.face.y1, m.face.x2, m.face.y2);
  t.clearance = m.clearance;
  t.allow_reverse = m.allow_reverse;
  t.appendages = static_cast<Appendages>(m.appendages);
  return t;
}

task_plan_t TaskPlanToLcm(const TaskPlanMessage& p) {
  task_plan_t m{};
  m.utime = p.utime;
  m.plan_id = p.plan_id;
  m.request_id = p.request_id;
  m.mission_id = p.mission_id;
  m.status = static_cast<int8_t>(p.plan.status);
  m.reason = p.plan.reason;
  for (const Task& t : p.plan.tasks) m.tasks.push_back(TaskToLcm(t));
  m.num_tasks = static_cast<int32_t>(m.tasks.size());
  return m;
}

TaskPlanMessage TaskPlanFromLcm(const task_plan_t& m) {
  if (m.status < task_plan_t::OK || m.status > task_plan_t::FAILED)
    throw InputError("task plan " + std::to_string(m.plan_id) + ": unknown status " + std::to_string(m.status));
  if (m.num_tasks < 0 || static_cast<size_t>(m.num_tasks) != m.tasks.size())
    throw InputError("task plan " + std::to_string(m.plan_id) + ": num_tasks " + std::to_string(m.num_tasks) +
                     " does not match the tasks");
  TaskPlanMessage p;
  p.utime = m.utime;
  p.plan_id = m.plan_id;
  p.request_id = m.request_id;
  p.mission_id = m.mission_id;
  p.plan.status = static_cast<PlanStatus>(m.status);
  p.plan.reason = m.reason;
  for (const task_t& t : m.tasks) p.plan.tasks.push_back(TaskFromLcm(t));
  return p;
}

task_request_t TaskRequestToLcm(const TaskRequest& r) {
  task_request_t m{};
  m.utime = r.utime;
  m.request_id = r.request_id;
  m.mission_id = r.mission_id;
  m.kind = static_cast<int8_t>(r.kind);
  m.pose = ToLcm(r.pose);
  m.face = ToLcm(r.face);
  m.depth = r.depth;
  m.clearance = r.clearance;
  return m;
}

TaskRequest TaskRequestFromLcm(const task_request_t& m) {
  if (m.kind != task_request_t::SURVEY_NEXT && m.kind != task_request_t::ADVANCE)
    throw InputError("unknown kind " + std::to_string(m.kind) + " (SURVEY_NEXT 0, ADVANCE 1)");
  if (!Finite(m.pose)) throw InputError("pose is not finite");
  if (!std::isfinite(m.clearance) || m.clearance < 0.0)
    throw InputError("clearance " + std::to_string(m.clearance) + " m is not a finite value >= 0");
  TaskRequest r;
  r.utime = m.utime;
  r.request_id = m.request_id;
  r.mission_id = m.mission_id;
  r.kind = static_cast<TaskRequestKind>(m.kind);
  r.pose = FromLcm(m.pose);
  r.depth = m.depth;
  r.clearance = m.clearance;
  if (r.kind == TaskRequestKind::kAdvance) {
    if (!Finite(m.face)) throw InputError("face is not finite");
    if (!std::isfinite(m.depth) || m.depth <= 0.0)
      throw InputError("depth " + std::to_string(m.depth) + " m is not > 0");
    r.face = FromLcm(m.face);
  }
  return r;
}

}  // namespace minenav
