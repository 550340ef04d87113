#include "logger/message_catalog.h"

#include "common/message_auth.h"

#include <cstdint>
#include <cstdio>

#include "common/node/conversions.h"
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
#include "minenav/message_json.hpp"
#include "minenav/wire_check.hpp"

namespace minenav {

namespace {

template <typename T>
std::string QualifiedName() {
  return std::string("minenav.") + T::getTypeName();
}

template <typename T>
MessageProbe Probe(const uint8_t* data, size_t size) {
  MessageProbe probe;
  probe.type_name = QualifiedName<T>();
  probe.known_type = true;
  T msg{};
  // The layout first: decode() trusts the payload's array counts (see wire_check.hpp).
  std::string why;
  if (size > static_cast<size_t>(INT32_MAX) || !wire::Check<T>(data, static_cast<int64_t>(size), &why)) {
    probe.error = "truncated or malformed " + probe.type_name + " payload (" + std::to_string(size) + " bytes): " + why;
    return probe;
  }
  int used = -1;
  try {
    used = msg.decode(data, 0, static_cast<int>(size));
  } catch (const std::exception&) {
    used = -1;
  }
  if (used < 0) {
    probe.error = "truncated or malformed " + probe.type_name + " payload (" + std::to_string(size) + " bytes)";
    return probe;
  }
  if (static_cast<size_t>(used) != size) {
    probe.error = probe.type_name + " decoded from " + std::to_string(used) + " of " + std::to_string(size) +
                  " bytes: " + std::to_string(size - static_cast<size_t>(used)) + " bytes left over";
    return probe;
  }
  probe.ok = true;
  if constexpr (requires { msg.utime; }) probe.utime = msg.utime;
  if constexpr (requires { msg.seq; }) {
    probe.sequence = msg.seq;
    probe.sequence_field = "seq";
  } else if constexpr (requires { msg.scan_id; }) {
    probe.sequence = msg.scan_id;
    probe.sequence_field = "scan_id";
  }
  return probe;
}

template <typename T>
bool DecodeToJson(const uint8_t* data, size_t size, nlohmann::json* out, std::string* error) {
  T msg{};
  if (size > static_cast<size_t>(INT32_MAX) ||
      !DecodeMessage(data, static_cast<int>(size), std::string(T::getTypeName()), &msg, error))
    return false;
  *out = ToJson(msg);
  return true;
}

template <typename T>
KnownMessageType Entry() {
  return {QualifiedName<T>(), T::getHash(), &Probe<T>, &DecodeToJson<T>, JsonSchemaText<T>()};
}

int64_t ReadFingerprint(const uint8_t* data) {
  uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v = (v << 8) | data[i];
  return static_cast<int64_t>(v);
}

}  // namespace

std::string FingerprintHex(int64_t fingerprint) {
  char buf[24];
  std::snprintf(buf, sizeof(buf), "0x%016llx",
                static_cast<unsigned long long>(static_cast<uint64_t>(fingerprint)));
  return buf;
}

const std::vector<KnownMessageType>& KnownMessageTypes() {
  static const std::vector<KnownMessageType> types = {
      Entry<ladar_scan_t>(),       Entry<odometry_t>(),         Entry<vehicle_truth_t>(),
      Entry<pose_estimate_t>(),    Entry<line_map_t>(),         Entry<contour_map_t>(),
      Entry<path_request_t>(),     Entry<path_t>(),             Entry<task_plan_t>(),
      Entry<task_status_t>(),      Entry<drive_command_t>(),    Entry<cutter_command_t>(),
      Entry<cutter_state_t>(),     Entry<heartbeat_t>(),        Entry<coordinator_command_t>(),
      Entry<mission_status_t>(),    Entry<task_request_t>(),
  };
  return types;
}

const KnownMessageType* FindKnownTypeByName(const std::string& name) {
  for (const auto& t : KnownMessageTypes())
    if (t.name == name) return &t;
  return nullptr;
}

const KnownMessageType* FindKnownTypeByFingerprint(const uint8_t* data, size_t size) {
  if (size < 8) return nullptr;
  const int64_t fp = ReadFingerprint(data);
  for (const auto& t : KnownMessageTypes())
    if (t.fingerprint == fp) return &t;
  return nullptr;
}

std::string ExpectedTypeForChannel(const std::string& channel) {
  // Exact names first; then the longest name that is a prefix followed by '_' (an
  // instance suffix such as POSE_IPE or LADAR_SCAN_FRONT).
  static const std::vector<std::pair<std::string, std::string>> kChannels = {
      {"LADAR_SCAN", "ladar_scan_t"},     {"ODOMETRY", "odometry_t"},
      {"SIM_TRUTH", "vehicle_truth_t"},   {"POSE", "pose_estimate_t"},
      {"CONTOUR_MAP", "contour_map_t"},   {"LINE_MAP", "line_map_t"},
      {"SIM_WORLD", "line_map_t"},
      {"PATH_REQUEST", "path_request_t"}, {"PATH", "path_t"},
      {"TASK_PLAN", "task_plan_t"},       {"TASK_STATUS", "task_status_t"},
      {"TASK_REQUEST", "task_request_t"}, {"DRIVE_PATH", "path_t"},
      {"CUT_TASK", "cutter_command_t"},
      {"DRIVE_COMMAND", "drive_command_t"}, {"CUTTER_COMMAND", "cutter_command_t"},
      {"CUTTER_STATE", "cutter_state_t"}, {"HEARTBEAT", "heartbeat_t"},
      {"COORDINATOR_COMMAND", "coordinator_command_t"}, {"MISSION_STATUS", "mission_status_t"},
  };
  for (const auto& [name, type] : kChannels)
    if (channel == name) return "minenav." + type;
  size_t best_len = 0;
  std::string best;
  for (const auto& [name, type] : kChannels) {
    if (channel.size() > name.size() + 1 && channel.compare(0, name.size(), name) == 0 &&
        channel[name.size()] == '_' && name.size() > best_len) {
      best_len = name.size();
      best = "minenav." + type;
    }
  }
  return best;
}

MessageProbe ProbeMessage(const std::string& channel, const uint8_t* data, size_t size) {
  // A signed command carries an authentication trailer after the message (common/message_auth.h).
  size = static_cast<size_t>(StripAuthTrailer(data, static_cast<int>(size)));
  const std::string expected = ExpectedTypeForChannel(channel);
  const KnownMessageType* actual = FindKnownTypeByFingerprint(data, size);
  MessageProbe probe;
  probe.type_name = expected;
  if (size < 8) {
    probe.known_type = !expected.empty();
    probe.error = "payload of " + std::to_string(size) + " bytes is shorter than an 8-byte fingerprint";
    return probe;
  }
  if (!expected.empty()) {
    const KnownMessageType* want = FindKnownTypeByName(expected);
    if (actual != want) {
      probe.known_type = true;
      probe.error = "fingerprint " + FingerprintHex(ReadFingerprint(data)) + " is not " + expected + "'s (" +
                    FingerprintHex(want->fingerprint) + ")" +
                    (actual ? "; it is " + actual->name : std::string("; not a minenav type"));
      return probe;
    }
    return want->probe(data, size);
  }
  if (!actual) {
    probe.ok = true;  // a foreign type on a channel we do not name: not ours to judge
    probe.type_name = "";
    return probe;
  }
  return actual->probe(data, size);
}

}  // namespace minenav
