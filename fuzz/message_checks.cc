#include "fuzz/message_checks.h"

#include <cmath>
#include <string>

#include "common/file_io.h"
#include "common/node/contour_map_conversions.h"
#include "common/node/conversions.h"
#include "common/node/heartbeat_conversion.h"
#include "planner/path_message.h"
#include "planner/path_planner_node.h"
#include "planner/se2_planner.h"
#include "planner/task_plan_message.h"
#include "tracker/cutter_conversions.h"

namespace minenav::fuzz {

namespace {

void Require(bool ok, const std::string& what) {
  if (!ok) throw InputError(what);
}

}  // namespace

void CheckAccepted(const contour_map_t& m) { (void)ContourMapFromLcm(m); }

// What the coordinator's COORDINATOR_COMMAND handler accepts (coordinator_node.cc).
void CheckAccepted(const coordinator_command_t& m) {
  Require(m.command >= coordinator_command_t::START && m.command <= coordinator_command_t::LOAD_MISSION,
          "coordinator_command_t.command " + std::to_string(m.command) + " is unknown");
}

void CheckAccepted(const cutter_command_t& m) {
  std::string why;
  Require(CutterCommandFromLcm(m, &why).has_value(), why);
}

void CheckAccepted(const cutter_state_t& m) {
  std::string why;
  Require(CutterStateFromLcm(m, &why).has_value(), why);
}

void CheckAccepted(const drive_command_t& m) { (void)FromLcm(m); }

void CheckAccepted(const heartbeat_t& m) { (void)HeartbeatSampleFromLcm(m, m.utime); }

void CheckAccepted(const ladar_scan_t& m) { (void)FromLcm(m); }

void CheckAccepted(const line_map_t& m) { (void)SegmentsFromLcm(m); }

// MISSION_STATUS is shown (viewer, log tools), not acted on: a known state and a finite progress.
void CheckAccepted(const mission_status_t& m) {
  Require(m.state >= mission_status_t::IDLE && m.state <= mission_status_t::WAITING,
          "mission_status_t.state " + std::to_string(m.state) + " is unknown");
  Require(std::isfinite(m.progress), "mission_status_t.progress is not finite");
}

void CheckAccepted(const odometry_t& m) { (void)FromLcm(m); }

void CheckAccepted(const path_request_t& m) {
  const std::string why = ValidateRequest(m, PathPlannerNodeOptions{});
  Require(why.empty(), "path_request_t: " + why);
}

void CheckAccepted(const path_t& m, bool check_motions) {
  Require(std::isfinite(m.start.x) && std::isfinite(m.start.y) && std::isfinite(m.start.theta),
          "path_t.start is not finite");
  Require(std::isfinite(m.length), "path_t.length is not finite");
  if (check_motions && m.feasible) (void)PathFromLcm(m, Se2PlannerOptions{}.turn_radius);
}

void CheckAccepted(const pose_estimate_t& m) { (void)FromLcm(m); }

void CheckAccepted(const task_plan_t& m) { (void)TaskPlanFromLcm(m); }

void CheckAccepted(const task_request_t& m) { (void)TaskRequestFromLcm(m); }

// What the coordinator's TASK_STATUS handler accepts (coordinator_node.cc).
void CheckAccepted(const task_status_t& m) {
  Require(m.state >= task_status_t::PENDING && m.state <= task_status_t::CANCELED,
          "task_status_t.state " + std::to_string(m.state) + " is unknown");
  Require(std::isfinite(m.progress), "task_status_t.progress is not finite");
}

void CheckAccepted(const vehicle_truth_t& m) { (void)FromLcm(m); }

}  // namespace minenav::fuzz
