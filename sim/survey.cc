#include "sim/survey.h"

#include <cmath>
#include <memory>

#include "common/segment_index.h"
#include "sensor_driver/ladar_simulator.h"

namespace minenav {

namespace {

// Separate random streams for the estimates and the ladar noise from one user seed.
uint64_t EstimateSeed(uint64_t seed) { return seed * 0x9E3779B97F4A7C15ull + 0x5EEDull; }

}  // namespace

std::string ValidateSurveyOptions(const SurveyOptions& o) {
  if (const std::string why = o.sensor.Validate(); !why.empty()) return why;
  if (!(o.station_interval > 0.0) || !std::isfinite(o.station_interval))
    return "station interval must be > 0 s";
  if (o.start_utime < 0) return "start utime must be >= 0";
  if (o.estimate == InitialEstimateKind::kPoseNoise) {
    const PoseNoise& n = o.pose_noise;
    if (!(n.sigma_x >= 0.0) || !(n.sigma_y >= 0.0) || !(n.sigma_theta >= 0.0))
      return "pose noise sigmas must be >= 0";
  }
  if (o.estimate == InitialEstimateKind::kDrift) {
    if (const std::string why = ValidateOdometryErrorOptions(o.drift); !why.empty()) return why;
  }
  return "";
}

void RunSurvey(const std::vector<std::vector<Segment>>& worlds, const std::vector<Station>& stations,
               const SurveyOptions& options, const std::function<void(const SurveyRecord&)>& sink,
               const std::function<void(int, int)>& progress) {
  if (const std::string why = ValidateSurveyOptions(options); !why.empty()) throw InputError(why);
  for (size_t k = 0; k < stations.size(); ++k) {
    if (stations[k].world < 0 || static_cast<size_t>(stations[k].world) >= worlds.size())
      throw InputError("station " + std::to_string(k) + " (data row " + std::to_string(k + 1) + ") uses world " +
                       std::to_string(stations[k].world) + " but only " + std::to_string(worlds.size()) +
                       " world(s) were given");
  }
  std::vector<Pose2> truth;
  truth.reserve(stations.size());
  for (const auto& s : stations) truth.push_back(s.pose);

  std::vector<Pose2> estimates = truth;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  switch (options.estimate) {
    case InitialEstimateKind::kTruth:
      break;
    case InitialEstimateKind::kPoseNoise:
      estimates = PerturbPoses(truth, options.pose_noise, EstimateSeed(options.seed));
      covariance.diagonal() << options.pose_noise.sigma_x * options.pose_noise.sigma_x,
          options.pose_noise.sigma_y * options.pose_noise.sigma_y,
          options.pose_noise.sigma_theta * options.pose_noise.sigma_theta;
      break;
    case InitialEstimateKind::kDrift: {
      std::vector<double> times(truth.size());
      for (size_t k = 0; k < times.size(); ++k) times[k] = static_cast<double>(k) * options.station_interval;
      estimates = DeadReckonAlong(truth, times, options.drift, EstimateSeed(options.seed));
      break;
    }
  }

  // One ray-casting index per world, built on first use.
  std::vector<std::unique_ptr<StaticSegmentIndex>> grids(worlds.size());
  const LadarSimulator simulator(options.sensor, options.seed);
  const auto interval_us = static_cast<int64_t>(std::llround(options.station_interval * 1e6));
  for (size_t k = 0; k < stations.size(); ++k) {
    const auto w = static_cast<size_t>(stations[k].world);
    if (!grids[w]) grids[w] = std::make_unique<StaticSegmentIndex>(worlds[w]);
    SurveyRecord rec;
    rec.index = static_cast<int>(k);
    rec.utime = options.start_utime + static_cast<int64_t>(k) * interval_us;
    rec.truth = truth[k];
    rec.estimate = estimates[k];
    rec.estimate_covariance = covariance;
    rec.world = stations[k].world;
    rec.world_changed = k == 0 || stations[k].world != stations[k - 1].world;
    rec.scan = simulator.Simulate(*grids[w], truth[k], options.sensor_offset, rec.utime, static_cast<int64_t>(k));
    sink(rec);
    if (progress) progress(static_cast<int>(k + 1), static_cast<int>(stations.size()));
  }
}

}  // namespace minenav
