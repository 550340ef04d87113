#pragma once
// task_plan_t / task_t / task_request_t (lcmtypes/) <-> the task planner's plain types
// (planner/task.h): what the task_planner publishes and what a coordinator reads back. Every
// conversion from a message validates it (enumerations in range, counts that match, finite
// numbers) and throws InputError with one line naming the field.

#include <cstdint>
#include <string>

#include "minenav/task_plan_t.hpp"
#include "minenav/task_request_t.hpp"
#include "minenav/task_t.hpp"
#include "planner/task.h"

namespace minenav {

struct TaskPlanMessage {
  int64_t utime = 0;
  int64_t plan_id = 0;
  int64_t request_id = 0;
  std::string mission_id;
  TaskPlan plan;
};

task_t TaskToLcm(const Task& task);
Task TaskFromLcm(const task_t& m);

task_plan_t TaskPlanToLcm(const TaskPlanMessage& plan);
TaskPlanMessage TaskPlanFromLcm(const task_plan_t& m);

task_request_t TaskRequestToLcm(const TaskRequest& request);
// Throws InputError: an unknown kind, a pose that is not finite, (ADVANCE) a face or depth
// that is not finite, a negative or non-finite clearance.
TaskRequest TaskRequestFromLcm(const task_request_t& m);

}  // namespace minenav
