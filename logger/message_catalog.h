#pragma once
// The minenav message types a log may hold, recognised by their LCM fingerprint (the
// first 8 bytes of every encoded message), and the channel names of DESIGN.md ("The
// bus") with the type each must carry. Tools use it to decode a log without being told
// what is in it, and to tell a wrong type or a truncated payload from a foreign one.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace minenav {

// What a probe learns from one payload.
struct MessageProbe {
  bool ok = false;
  std::string type_name;       // decoded type, or the expected one on failure ("" = unknown)
  std::string error;           // one line when !ok
  bool known_type = false;     // fingerprint matches a minenav type
  std::optional<int64_t> utime;
  std::optional<int64_t> sequence;  // seq, or scan_id for types without seq
  std::string sequence_field;       // "seq" or "scan_id"
};

struct KnownMessageType {
  std::string name;  // e.g. "minenav.ladar_scan_t"
  int64_t fingerprint = 0;
  std::function<MessageProbe(const uint8_t* data, size_t size)> probe;
  // Every field as JSON (minenav/message_json.hpp, generated from the .lcm file): false and
  // *error (one line) when the payload does not decode (wire check first).
  std::function<bool(const uint8_t* data, size_t size, nlohmann::json* out, std::string* error)> to_json;
  std::string_view json_schema;  // the JSON Schema of what to_json makes
};

// Every top-level minenav message type.
const std::vector<KnownMessageType>& KnownMessageTypes();
const KnownMessageType* FindKnownTypeByName(const std::string& name);
// nullptr when the payload is shorter than 8 bytes or the fingerprint is foreign.
const KnownMessageType* FindKnownTypeByFingerprint(const uint8_t* data, size_t size);

// The type a channel must carry by its name ("LADAR_SCAN", "POSE_IPE", "ODOMETRY_2"...),
// or "" for channels the design does not name. A suffix after '_' names an instance.
std::string ExpectedTypeForChannel(const std::string& channel);

// Decodes the payload as the channel's expected type (or, for channels without one, as
// whatever minenav type its fingerprint names). ok = false with a one-line error for a
// payload shorter than a fingerprint, a fingerprint of another type on a named channel,
// a truncated or malformed payload, or bytes left over after the message (an authentication
// trailer, common/message_auth.h, is not left over: it is stripped first). A foreign
// fingerprint on an unnamed channel is ok with known_type = false.
MessageProbe ProbeMessage(const std::string& channel, const uint8_t* data, size_t size);

std::string FingerprintHex(int64_t fingerprint);

}  // namespace minenav
