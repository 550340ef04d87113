#pragma once
// path_planner live (planner/README.md "Live"): answers PATH_REQUEST with PATH on the
// contour map the mapper publishes (CONTOUR_MAP), and replans the active path when the map
// changes under it. The process (path_planner_main.cc) only declares these options and
// wires the node.
//
//   PATH_REQUEST  validated on the node thread (NaN, tolerances, clearance; one line each),
//                 then planned on the BackgroundWorker (the node loop never waits for a
//                 search) against the walls of the latest map and, unless the request allows
//                 unknown space, its frontiers (planner/contour_free_space.h); each search is
//                 bounded by `deadline` (SearchLimits::stop_requested) and the answer names
//                 the bound that stopped it.
//   CONTOUR_MAP   plain or zlib (common/node/contour_map_conversions.h). One Se2Planner per
//                 (map version, clearance, collision step, allow_unknown, allow_reverse), so
//                 repeated requests to a goal on one map reuse its cached heuristic. A new version re-checks the rest of the
//                 active path (from the latest POSE's closest point on it) with
//                 Se2Planner::PieceCollides; when blocked the node replans from the latest
//                 pose to the same goal and publishes a PATH with the same request_id and the
//                 status "replanned: <why>".
//   POSE          the vehicle's estimate (pose_estimate_t; converged estimates only).
//   DRIVE_PATH    path_t: the path the tracker drives now (the coordinator forwards one of the
//                 answers there, and may hold the next subtask's path planned ahead). Once
//                 anything arrives there, the active path (the one re-checked and replanned) is
//                 the answer last forwarded on it (feasible = false: none); before that, the
//                 last feasible answer.
//   A repeated request_id (the coordinator re-sends until it hears the answer) is answered
//   again with the stored answer, or ignored while its search runs: never planned twice.
//   PATH          path_t: feasible with the motions, or feasible = false and the one-line reason.
// A start the planner finds in collision is where the vehicle stands: frontiers through its
// footprint are ignored (FrontiersAwayFrom), and within the clearance of a wall it leaves with
// the clearance it has (Se2Planner::LeavingOptions); the status says which. Only a footprint
// in contact with a wall is refused.
// A request with allow_reverse = false is planned with reversing priced at 100 m a metre and
// refused when the path found still reverses.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <map>
#include <set>
#include <memory>
#include <optional>
#include <string>

#include "common/config.h"
#include "common/node/background_worker.h"
#include "common/node/first_map_wait.h"
#include "common/node/node_runtime.h"
#include "minenav/contour_map_t.hpp"
#include "minenav/path_request_t.hpp"
#include "minenav/path_t.hpp"
#include "planner/path_message.h"  // PathToLcm, NoPathToLcm
#include "planner/contour_free_space.h"
#include "planner/footprint.h"
#include "planner/motion.h"
#include "planner/search_limits.h"
#include "planner/se2_planner.h"

namespace minenav {

struct PathPlannerNodeOptions {
  std::string request_channel = "PATH_REQUEST";
  std::string map_channel = "CONTOUR_MAP";
  std::string pose_channel = "POSE";
  std::string path_channel = "PATH";
  std::string drive_path_channel = "DRIVE_PATH";
  // s after the start in which a request that comes before any map is left for its repeat
  // (common/node/first_map_wait.h: a restarted planner gets the map within 2 s). Default 10.
  double first_map_wait = 10.0;
  double deadline = 5.0;            // s of wall time per search (request or replan; not the planner's setup for a new map). Default 5.
  double default_clearance = 0.1;   // m, used when a request's clearance is 0. Default 0.1.
  double max_clearance = 2.0;       // m, larger requested clearances are refused. Default 2.
  double max_tolerance = 5.0;       // m (position) and rad (heading) a request may give. Default 5.
  double speed = 0.076;             // m/s, the speed limit written on every segment (the miner's cruise). Default 0.076.
  int queue_capacity = 4;           // --search-queue: searches that may wait for the worker; the oldest is dropped. Default 4.
  double poll_period = 0.02;        // s between looks at the worker's answers. Default 0.02.
  Se2PlannerOptions planner;        // planner.clearance is replaced by the request's
  SearchLimits search;
  FreeSpaceOptions free_space;
};

// Every option: channels, deadline, clearances, ..., planner.*, search.*, free_space.*.
void DeclareOptions(ConfigSchema& schema, PathPlannerNodeOptions& options);
// "" when usable, else one line.
std::string ValidateOptions(const PathPlannerNodeOptions& options);

// "" when the request can be planned, else the one-line reason (NaN, tolerances, clearance).
std::string ValidateRequest(const path_request_t& request, const PathPlannerNodeOptions& options);

class PathPlannerNode {
 public:
  // Subscribes and adds the worker's poll timer (call after runtime.Start()).
  PathPlannerNode(NodeRuntime& runtime, PathPlannerNodeOptions options, Footprint footprint);
  ~PathPlannerNode();
  int Run() { return runtime_.Run(); }

  // Counters (node thread).
  int64_t requests() const { return requests_; }
  int64_t answers() const { return answers_; }
  int64_t replans() const { return replans_; }
  int64_t map_version() const;
  bool has_active_path() const { return active_.has_value(); }
  // Se2Planners built so far (any thread): one per map version, clearance, allow_unknown and allow_reverse.
  int64_t planners_built() const { return planners_built_.load(); }

  struct MapSnapshot;  // one CONTOUR_MAP version, shared with the worker
  struct Job;
  struct Answer;

 private:
  void OnRequest(const path_request_t& request);
  void OnMap(const contour_map_t& map);
  void OnDrivePath(const path_t& path);
  void Remember(const Answer& answer);
  void Publish(const path_t& path);
  void Poll();
  Answer Handle(Job& job);  // worker thread

  NodeRuntime& runtime_;
  FirstMapWait first_map_wait_;
  PathPlannerNodeOptions options_;
  Footprint footprint_;
  std::shared_ptr<const MapSnapshot> map_;
  std::optional<Pose2> pose_;
  // The last feasible answer, and the request it answers (the goal and settings of a replan).
  struct Active {
    path_request_t request;
    PlannedPath path;
  };
  std::optional<Active> active_;
  bool follow_drive_path_ = false;  // DRIVE_PATH names the active path (something arrived there)
  // The answers of recent requests (repeats are answered from here; DRIVE_PATH names one).
  struct Answered {
    path_t message{};
    std::optional<Active> path;
  };
  std::map<int64_t, Answered> answered_;
  std::deque<int64_t> answered_order_;
  std::set<int64_t> pending_;  // request ids queued or being searched
  int64_t requests_ = 0, answers_ = 0, replans_ = 0;
  std::atomic<int64_t> planners_built_{0};
  // Worker-thread state: the planners of the map version in force.
  struct PlannerCache;
  std::unique_ptr<PlannerCache> cache_;
  std::unique_ptr<BackgroundWorker<Job, Answer>> worker_;  // last: stopped first
};

}  // namespace minenav
