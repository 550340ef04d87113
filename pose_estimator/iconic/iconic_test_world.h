#pragma once
// Tiny inline worlds for the iconic estimator's tests: exact scans by ray casting
// (common/geometry.h CastRay), optional Gaussian range noise.

#include <cstdint>
#include <random>
#include <vector>

#include "common/geometry.h"
#include "common/scan.h"

namespace minenav::testing {

// A 20 x 12 m room with a 2 x 2 m pillar and an L-shaped alcove: no symmetry, so the
// pose is fully observable.
std::vector<Segment> RoomWorld();

// A scan of `world` from vehicle pose `pose` (sensor at the vehicle origin), `n` readings
// over 360 degrees, range noise sigma (m), readings that hit nothing are NaN.
LadarScan ExactScan(const std::vector<Segment>& world, const Pose2& pose, int n = 720, double sigma = 0.0,
                    uint32_t seed = 1, int64_t utime = 0);

}  // namespace minenav::testing
