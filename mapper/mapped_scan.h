#pragma once
// A scan that has been inserted into the map: its partial scans (vehicle frame) and the
// current estimate of its pose. Contour fitting and concurrent refinement work on these.

#include <vector>

#include "common/pose2.h"
#include "mapper/scan_preprocessing.h"

namespace minenav::mapper {

struct MappedScan {
  PreprocessedScan scan;
  Pose2 pose;          // world_T_vehicle, current estimate
  bool fixed = false;  // the first scan anchors the map frame and is never moved
};

}  // namespace minenav::mapper
