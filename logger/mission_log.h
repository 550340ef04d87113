#pragma once
// Reads the log of a whole mission (lcm-logger's recording of the fleet) into the plain
// MissionRecord that evaluation/mission_evaluation.h judges: SIM_TRUTH, POSE, ODOMETRY,
// SIM_WORLD, PATH, DRIVE_PATH, TASK_STATUS, MISSION_STATUS, TASK_PLAN (scan stations),
// HEARTBEAT, and the last CONTOUR_MAP. Scans and everything else are skipped undecoded.
//
// A message that does not decode, or holds invalid values, is counted (MissionRecord::
// bad_messages, the first one named) and skipped. A log that ends in the middle of an event
// (the logger killed while writing) or is damaged further on is read up to the damage, and
// MissionRecord::damage says where: the report is made from what came before.

#include <optional>
#include <set>
#include <string>

#include "common/message_auth.h"
#include "common/node/auth_bus.h"
#include "common/node/contour_map_conversions.h"
#include "evaluation/mission_record.h"

namespace minenav {

struct MissionLogChannels {
  std::string truth = "SIM_TRUTH";
  std::string pose = "POSE";
  std::string odometry = "ODOMETRY";
  std::string world = "SIM_WORLD";
  std::string path = "PATH";
  std::string drive_path = "DRIVE_PATH";
  std::string task_status = "TASK_STATUS";
  std::string mission_status = "MISSION_STATUS";
  std::string task_plan = "TASK_PLAN";
  std::string heartbeat = "HEARTBEAT";
  std::string contour_map = "CONTOUR_MAP";
};

// The fleet's key, to read a log as the fleet's receivers did: a message on a signed channel
// that does not verify (an attacker's forgery, replay, tampering or unsigned copy; the event's
// timestamp is its receive time) is counted in MissionRecord::auth_refused and not used.
struct MissionLogAuth {
  AuthKeyRing keys;
  std::set<std::string, std::less<>> signed_channels = ParseChannelList(AuthOptions{}.signed_channels);
  double max_age = AuthOptions{}.max_age;  // s
};

struct MissionLog {
  MissionRecord record;
  std::optional<ContourMapMessage> last_contour_map;  // the last CONTOUR_MAP that decoded
};

// Throws InputError when the file cannot be opened.
MissionLog ReadMissionLog(const std::string& path, const MissionLogChannels& channels = {},
                          const MissionLogAuth* auth = nullptr);

}  // namespace minenav
