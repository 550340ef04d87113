// Fuzz target: every LCM message type the fleet receives, through the project's own decode
// path: the bytes arrive on one channel per type of a FakeBus, subscribed with Subscribe<T>
// (common/node/bus.h): the wire check (minenav/wire_check.hpp), lcm-gen's decode(), the
// timestamp window (AcceptStamp) and then the conversion the receiving nodes run
// (message_checks.h: FromLcm, ContourMapFromLcm with its zlib inflation, PathFromLcm, ...).
// The fingerprint in the first 8 bytes says which type the payload claims to be; the
// dictionary (fuzz/dict/lcm.dict) holds every fingerprint.
//
// Findings: a crash, a sanitizer report, an allocation past -malloc_limit_mb (issue 11's
// counts that make receivers allocate gigabytes), an exception other than InputError out of
// a conversion, and a decoded message that does not survive encode -> decode unchanged.

#include <cstdint>
#include <string>
#include <vector>

#include "common/file_io.h"
#include "common/log.h"
#include "common/node/conversions.h"
#include "common/node/fake_bus.h"
#include "fuzz/message_checks.h"

namespace minenav::fuzz {
namespace {

constexpr int64_t kReceiveTime = 1'700'000'000'000'000;  // us

// Encoding the decoded message and decoding it again gives the same encoding: a decoder that
// reads a different layout than the encoder writes would pass garbage on.
template <typename T>
void CheckRoundTrip(const T& m, const std::string& channel) {
  const std::vector<uint8_t> once = EncodeMessage(m);
  T again{};
  std::string error;
  if (!DecodeMessage(once.data(), static_cast<int>(once.size()), channel, &again, &error))
    Fail("a decoded " + std::string(T::getTypeName()) + " does not decode once re-encoded: " + error);
  if (EncodeMessage(again) != once) Fail("a decoded " + std::string(T::getTypeName()) + " changes on a round trip");
}

template <typename T>
void SubscribeType(FakeBus& bus) {
  const std::string channel = T::getTypeName();
  Subscribe<T>(bus, channel, [channel](const T& m) {
    CheckRoundTrip(m, channel);
    try {
      CheckAccepted(m);
    } catch (const InputError&) {
      throw;  // rejected in one line: what the bus counts as bad
    } catch (const std::exception& e) {
      Fail("the conversion of a " + channel + " threw " + e.what() + " (not an InputError)");
    }
  });
}

FakeBus& MakeBus() {
  static FakeBus* bus = [] {
    SetLogLevel(LogLevel::kError);  // the bus logs each bad message (rate-limited per channel)
    auto* b = new FakeBus;
    b->set_max_stamp_lead_us(10'000'000);
    SubscribeType<contour_map_t>(*b);
    SubscribeType<coordinator_command_t>(*b);
    SubscribeType<cutter_command_t>(*b);
    SubscribeType<cutter_state_t>(*b);
    SubscribeType<drive_command_t>(*b);
    SubscribeType<heartbeat_t>(*b);
    SubscribeType<ladar_scan_t>(*b);
    SubscribeType<line_map_t>(*b);
    SubscribeType<mission_status_t>(*b);
    SubscribeType<odometry_t>(*b);
    SubscribeType<path_request_t>(*b);
    SubscribeType<path_t>(*b);
    SubscribeType<pose_estimate_t>(*b);
    SubscribeType<task_plan_t>(*b);
    SubscribeType<task_request_t>(*b);
    SubscribeType<task_status_t>(*b);
    SubscribeType<vehicle_truth_t>(*b);
    return b;
  }();
  return *bus;
}

}  // namespace
}  // namespace minenav::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  FakeBus& bus = fuzz::MakeBus();
  // The same bytes on every type's channel: a receiver of the wrong type sees them too.
  for (const char* type : {"contour_map_t", "coordinator_command_t", "cutter_command_t", "cutter_state_t",
                           "drive_command_t", "heartbeat_t", "ladar_scan_t", "line_map_t", "mission_status_t",
                           "odometry_t", "path_request_t", "path_t", "pose_estimate_t", "task_plan_t",
                           "task_request_t", "task_status_t", "vehicle_truth_t"})
    bus.Inject(type, std::vector<uint8_t>(data, data + size), fuzz::kReceiveTime);
  bus.HandleFor(0);
  return 0;
}
