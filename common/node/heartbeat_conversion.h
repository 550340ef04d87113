#pragma once
// A HEARTBEAT message as the fleet library sees it (heartbeat_monitor.h has no LCM).

#include <cstdint>

#include "common/heartbeat_monitor.h"
#include "minenav/heartbeat_t.hpp"

namespace minenav {

// `received`: when it arrived, on the receiver's clock (µs). Throws InputError for a state
// that is none of heartbeat_t's or negative counters (the bus counts it as bad).
HeartbeatSample HeartbeatSampleFromLcm(const heartbeat_t& message, int64_t received);

}  // namespace minenav
