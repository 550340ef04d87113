#pragma once
// An offline ladar survey (thesis 5.2.1, 5.3): the vehicle stands at each station in turn
// and takes one scan of the world; each scan comes with the true pose and an initial pose
// estimate made either as truth plus independent noise per station (what the thesis
// did: "sigma_x = 0.33, sigma_y = 0.33, sigma_theta = 3.33") or as dead reckoning
// accumulated along the station sequence (what a real miner's odometry would give).
//
// A changing world (thesis 4.8): several worlds may be given and each station names the
// one it sees (the stations CSV column `world`), so one survey shows doors opening, boxes
// appearing or a face advancing between stations. Each record says which world was used
// and whether it differs from the previous station's, so the log writer can record the
// world when it becomes active.
//
// Plain C++ (no LCM): `log_tool survey` writes the records into a log. Deterministic for
// a seed: ladar noise depends on (seed, scan_id); the initial estimates on the seed.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/file_io.h"
#include "common/geometry.h"
#include "common/scan.h"
#include "sensor_driver/ladar_model.h"
#include "sim/odometry_model.h"

namespace minenav {

enum class InitialEstimateKind {
  kTruth,      // estimates equal truth
  kPoseNoise,  // truth + independent Gaussian noise per station (PoseNoise)
  kDrift,      // dead reckoning along the station sequence (OdometryErrorOptions)
};

struct SurveyOptions {
  LadarModel sensor = LadarModel::Typhoon();
  Pose2 sensor_offset;           // sensor in the vehicle frame (m, m, rad)
  uint64_t seed = 1;
  InitialEstimateKind estimate = InitialEstimateKind::kTruth;
  PoseNoise pose_noise;          // for kPoseNoise: sigma_x, sigma_y (m), sigma_theta (rad)
  OdometryErrorOptions drift;    // for kDrift
  int64_t start_utime = 1'000'000'000'000'000;  // us, utime of the first scan
  double station_interval = 1.0; // s between the scans of consecutive stations
};

// "" when usable, else a one-line reason.
std::string ValidateSurveyOptions(const SurveyOptions& options);

struct SurveyRecord {
  int index = 0;         // station number, = scan_id
  int64_t utime = 0;     // us; the scan's utime, key into truth.csv
  Pose2 truth;           // vehicle in the world frame
  Pose2 estimate;        // initial estimate (ODOMETRY)
  Eigen::Matrix3d estimate_covariance = Eigen::Matrix3d::Zero();  // known for kPoseNoise, else 0
  int world = 0;                 // index into the worlds: the one this scan was ray-cast in
  bool world_changed = false;    // first station, or a world other than the previous station's
  LadarScan scan;
};

// Simulates every station in order and hands each record to `sink` (so a long survey
// never holds all scans). `worlds[station.world]` is the world a station sees. Throws
// InputError (one line) for a station whose world index is out of range or bad options.
// `progress(done, total)` is called after each station if given.
void RunSurvey(const std::vector<std::vector<Segment>>& worlds, const std::vector<Station>& stations,
               const SurveyOptions& options, const std::function<void(const SurveyRecord&)>& sink,
               const std::function<void(int, int)>& progress = {});

}  // namespace minenav
