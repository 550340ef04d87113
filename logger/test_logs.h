#pragma once
// Small logs built inline for the logger tests: a square room, a few stations, scans
// ray-cast by brute force (common/geometry.h), truth, odometry and a POSE channel.

#include <string>
#include <vector>

#include "common/file_io.h"
#include "common/geometry.h"
#include "common/scan.h"

namespace minenav::logger_test {

struct TestRun {
  std::vector<Segment> world;
  std::vector<StampedPose> truth, odometry, estimates;
  std::vector<LadarScan> scans;
};

// A 10 x 8 m room, `stations` poses inside it 1 s apart, scans of `points` readings.
TestRun MakeTestRun(int stations = 5, int points = 360);

// Writes ODOMETRY, SIM_TRUTH, POSE_IPE and LADAR_SCAN for each station, event time = utime.
void WriteTestLog(const std::string& path, const TestRun& run);

// A fresh path under the test's temporary directory.
std::string TempPath(const std::string& name);

std::string ReadAll(const std::string& path);
bool FileExists(const std::string& path);

}  // namespace minenav::logger_test
