#pragma once
// task_planner live (planner/README.md "Task planner"): answers every TASK_REQUEST with a
// TASK_PLAN carrying its request_id. The process (task_planner_main.cc) only declares these
// options and wires the node.
//
//   TASK_REQUEST  decoded and checked on the node thread (kind, finite pose, face and depth,
//                 clearance in [0, max_clearance]; a map to plan on): a bad one is answered
//                 FAILED with the one-line reason at once (and counted in HEARTBEAT
//                 messages_bad). A request_id answered before is answered again with the same
//                 plan (the coordinator re-sends until it hears one), never planned twice; one
//                 still being planned is not queued again.
//                 SURVEY_NEXT: the next scan station (survey_planner.h) on the latest contour
//                 map; ADVANCE: box cut, slab cut(s), back out (advance_planner.h) on the latest
//                 LINE_MAP when line_map_channel is set and one arrived, else the contour map.
//                 Planning runs on the BackgroundWorker (common/node/background_worker.h): the
//                 node loop never waits for it; a full queue drops the oldest waiting request
//                 (answered FAILED "dropped", not remembered: a re-send is planned). Each plan's
//                 path-planner searches stop at `deadline` s of wall time (live). In batch
//                 (--log) planning is synchronous on the node thread and has no deadline (the
//                 expansion budgets bound it): a batch run is repeatable.
//   CONTOUR_MAP   plain or zlib (common/node/contour_map_conversions.h); the walls and
//                 frontiers are made once per version on the worker.
//   LINE_MAP      optional (line_map_channel): walls only.
//   POSE          converged estimates: positions at least trail_spacing apart are kept as
//                 places the ladar has looked from (the live mapper scans while the vehicle
//                 drives); with the poses of earlier SURVEY_NEXT requests (the vehicle scanned
//                 where it asked from) they are the survey's visited stations.
//   TASK_PLAN     task_plan_t: plan_id (the node's count), request_id, mission_id, status OK /
//                 COMPLETE / FAILED, the one-line reason, the tasks.

#include <atomic>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/node/background_worker.h"
#include "common/node/first_map_wait.h"
#include "common/node/node_runtime.h"
#include "minenav/contour_map_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/task_plan_t.hpp"
#include "minenav/task_request_t.hpp"
#include "planner/advance_planner.h"
#include "planner/contour_free_space.h"
#include "planner/footprint.h"
#include "planner/planner_batch.h"
#include "planner/se2_planner.h"
#include "planner/search_limits.h"
#include "planner/survey_planner.h"
#include "planner/task_plan_message.h"

namespace minenav {

struct TaskPlannerNodeOptions {
  std::string request_channel = "TASK_REQUEST";
  std::string map_channel = "CONTOUR_MAP";
  std::string line_map_channel;  // "" = not subscribed; else ADVANCE plans on the latest LINE_MAP there. Default "".
  std::string pose_channel = "POSE";
  std::string plan_channel = "TASK_PLAN";
  // s after the start in which a request that comes before any map is left for its repeat
  // (common/node/first_map_wait.h). Default 10.
  double first_map_wait = 10.0;
  // "W,L" (m: a rectangle centred on the pose) or a footprint JSON file: the path planner's
  // --footprint, the 3.3 x 10 m miner by default.
  std::string footprint = PlannerBatchFlags{}.footprint;
  double deadline = 5.0;           // s of wall time the path-planner searches of one plan may take (live). Default 5.
  double default_clearance = 0.1;  // m, used when a request's clearance is 0. Default 0.1.
  double max_clearance = 2.0;      // m, larger requested clearances are refused. Default 2.
  double trail_spacing = 2.0;      // m between the POSE positions kept as places scanned from; 0 = none. Default 2.
  int max_trail = 2000;            // positions kept (the oldest go first). Default 2000.
  int queue_capacity = 4;          // --plan-queue: requests that may wait for the worker. Default 4.
  int answers_kept = 256;          // answers remembered by request_id (the oldest go first). Default 256.
  double poll_period = 0.02;       // s between looks at the worker's answers. Default 0.02.
  AdvanceOptions advance;
  SurveyPlannerOptions survey;
  Se2PlannerOptions planner;  // planner.clearance is replaced by the request's
  SearchLimits search;
  FreeSpaceOptions free_space;
};

// Every option: channels, footprint, deadline, clearances, ..., advance.*, survey.*, the
// path planner's (as path_planner declares them), search.*, free_space.*.
void DeclareOptions(ConfigSchema& schema, TaskPlannerNodeOptions& options);
// "" when usable, else one line.
std::string ValidateOptions(const TaskPlannerNodeOptions& options);

class TaskPlannerNode {
 public:
  // Subscribes and adds the worker's poll timer (call after runtime.Start()).
  TaskPlannerNode(NodeRuntime& runtime, TaskPlannerNodeOptions options, Footprint footprint);
  ~TaskPlannerNode();
  int Run() { return runtime_.Run(); }

  // Counters (node thread).
  int64_t requests() const { return requests_; }
  int64_t answers() const { return answers_; }
  int64_t repeats() const { return repeats_; }  // requests answered again from memory
  int64_t plans() const { return next_plan_id_ - 1; }
  size_t visited() const { return visited_.size(); }
  // Path planners built (any thread): a request on a map version that an earlier request
  // planned on with the same clearance builds none.
  int64_t planners_built() const { return planners_built_.load(); }

  struct Job;
  struct Answer;
  struct MapSnapshot;

 private:
  void OnRequest(const task_request_t& message);
  void OnContourMap(const contour_map_t& message);
  void OnLineMap(const line_map_t& message);
  void OnPose(const Pose2& pose);
  // Publishes on plan_channel (stamped now); remembered by request_id unless `remember` is false.
  void Publish(task_plan_t plan, bool remember);
  void Poll();
  Answer Plan(Job& job);  // worker thread (node thread in batch)

  NodeRuntime& runtime_;
  FirstMapWait first_map_wait_;
  TaskPlannerNodeOptions options_;
  Footprint footprint_;
  std::shared_ptr<const MapSnapshot> contour_map_, line_map_;
  std::vector<Pose2> visited_;               // places the ladar looked from
  std::map<int64_t, task_plan_t> answered_;  // by request_id
  std::deque<int64_t> answered_order_;       // oldest first
  std::set<int64_t> pending_;                // request_ids being planned
  int64_t requests_ = 0, answers_ = 0, repeats_ = 0, next_plan_id_ = 1;
  std::atomic<int64_t> planners_built_{0};
  // Worker-thread state: the task map of the contour map version in force.
  struct MapCache;
  std::unique_ptr<MapCache> cache_;
  std::unique_ptr<BackgroundWorker<Job, Answer>> worker_;  // last: stopped first (null in batch)
};

}  // namespace minenav
