#pragma once
// A pose given as text on a command line or in a config file (a sensor's mounting, a start
// pose): "x,y,theta" in m, m and rad (or e.g. 90deg); theta is normalised to (-pi, pi].

#include <string>
#include <vector>

#include "common/angle.h"
#include "common/config.h"
#include "common/pose2.h"

namespace minenav {

// Throws UsageError naming `what` (the flag) unless `text` holds three numbers.
inline Pose2 ParsePoseText(const std::string& text, const std::string& what) {
  const std::vector<double> p = ParseNumberList(text, what, 3);
  return Pose2(p[0], p[1], NormalizeAngle(p[2]));
}

}  // namespace minenav
