#pragma once
// What the fleet's receivers accept of each LCM message type, as one call per type: the
// conversion the receiving nodes run after decoding (FromLcm and its siblings), throwing
// InputError for what they reject. The fuzz targets use it twice: on hostile input (a
// rejection is fine, a crash or any other exception is a finding) and on what a node
// publishes (a node must never pass on what its receivers would reject: a NaN in, a NaN out).

#include <cstdint>
#include <string>
#include <vector>

#include "fuzz/finding.h"
#include "minenav/contour_map_t.hpp"
#include "minenav/coordinator_command_t.hpp"
#include "minenav/cutter_command_t.hpp"
#include "minenav/cutter_state_t.hpp"
#include "minenav/drive_command_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/mission_status_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/path_request_t.hpp"
#include "minenav/path_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "minenav/task_plan_t.hpp"
#include "minenav/task_request_t.hpp"
#include "minenav/task_status_t.hpp"
#include "minenav/vehicle_truth_t.hpp"

namespace minenav::fuzz {

// Each throws InputError (common/file_io.h) when a receiver of the fleet would reject the
// message. `path_t` checks a feasible path's motions (PathFromLcm at kFuzzTurnRadius) only when
// `check_motions` (the coordinator forwards paths it does not interpret), at the planner's
// and the tracker's default turning radius.
void CheckAccepted(const contour_map_t& m);
void CheckAccepted(const coordinator_command_t& m);
void CheckAccepted(const cutter_command_t& m);
void CheckAccepted(const cutter_state_t& m);
void CheckAccepted(const drive_command_t& m);
void CheckAccepted(const heartbeat_t& m);
void CheckAccepted(const ladar_scan_t& m);
void CheckAccepted(const line_map_t& m);
void CheckAccepted(const mission_status_t& m);
void CheckAccepted(const odometry_t& m);
void CheckAccepted(const path_request_t& m);
void CheckAccepted(const path_t& m, bool check_motions = true);
void CheckAccepted(const pose_estimate_t& m);
void CheckAccepted(const task_plan_t& m);
void CheckAccepted(const task_request_t& m);
void CheckAccepted(const task_status_t& m);
void CheckAccepted(const vehicle_truth_t& m);

}  // namespace minenav::fuzz
