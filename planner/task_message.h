#pragma once
// task_t / task_plan_t / task_request_t (lcmtypes/) <-> the plain Task, TaskPlan and
// TaskRequest of planner/task.h, shared by the task_planner and coordinator nodes. FromLcm
// validates (kinds, finite poses and numbers, counts) and throws InputError with one line
// naming the field.

#include "minenav/task_plan_t.hpp"
#include "minenav/task_request_t.hpp"
#include "minenav/task_t.hpp"
#include "planner/task.h"

namespace minenav {

task_t ToLcm(const Task& t);
Task FromLcm(const task_t& m);

task_plan_t ToLcm(const TaskPlan& p, int64_t utime);
TaskPlan FromLcm(const task_plan_t& m);

task_request_t ToLcm(const TaskRequest& r, int64_t utime);
TaskRequest FromLcm(const task_request_t& m);

}  // namespace minenav
