#pragma once
// Free functions between LCM messages (minenav::*_t) and the plain types algorithms use.
// FromLcm validates what it can (sizes, finiteness) and throws InputError naming the
// field, so nodes can reject a bad message in one line and go on.

#include <exception>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "common/pose_estimate.h"
#include "common/scan.h"
#include "common/vehicle_state.h"
#include "minenav/drive_command_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/pose2d_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "minenav/vehicle_truth_t.hpp"
#include "minenav/wire_check.hpp"

namespace minenav {

pose2d_t ToLcm(const Pose2& p);
Pose2 FromLcm(const pose2d_t& m);

ladar_scan_t ToLcm(const LadarScan& s);
LadarScan FromLcm(const ladar_scan_t& m);

odometry_t ToLcm(const OdometryReading& o);
OdometryReading FromLcm(const odometry_t& m);

vehicle_truth_t ToLcm(const TruthReading& t);
TruthReading FromLcm(const vehicle_truth_t& m);

drive_command_t ToLcm(const DriveCommand& c);
DriveCommand FromLcm(const drive_command_t& m);

pose_estimate_t ToLcm(const PoseEstimate& e);
PoseEstimate FromLcm(const pose_estimate_t& m);

line_map_t SegmentsToLcm(const std::vector<Segment>& segments, int64_t utime, int64_t version,
                         const std::string& name);
std::vector<Segment> SegmentsFromLcm(const line_map_t& m);

// Decodes a raw LCM payload into T. Returns false and sets *error (one line naming the
// channel and the reason: wrong fingerprint, truncated, a count that does not fit the
// payload) when it does not decode.
//
// The payload's layout is checked first (minenav/wire_check.hpp, generated from the .lcm
// files): lcm-gen's decode() trusts the array counts in the payload, so a hostile count
// makes it read past the buffer (LCM 1.3.1 overflows `sizeof(T) * count` in an int) or
// zero-fill gigabytes before it notices. After the check, decode() allocates at most a
// few times the payload's size.
template <typename T>
bool DecodeMessage(const void* data, int size, const std::string& channel, T* out, std::string* error) {
  *out = T{};
  std::string why;
  if (data == nullptr || size < 0 || !wire::Check<T>(data, size, &why)) {
    *error = "channel " + channel + ": cannot decode " + std::to_string(size) + " bytes as " +
             T::getTypeName() + " (" + (why.empty() ? "no payload" : why) + ")";
    return false;
  }
  int used = -1;
  try {
    used = out->decode(data, 0, size);
  } catch (const std::exception&) {
    used = -1;
  }
  if (used < 0) {
    *error = "channel " + channel + ": cannot decode " + std::to_string(size) + " bytes as " +
             T::getTypeName() + " (wrong type/fingerprint or truncated)";
    return false;
  }
  return true;
}

// Encodes any LCM message into bytes.
template <typename T>
std::vector<uint8_t> EncodeMessage(const T& msg) {
  std::vector<uint8_t> buf(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return buf;
}

}  // namespace minenav
