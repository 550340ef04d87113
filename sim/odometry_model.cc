#include "sim/odometry_model.h"

#include <cmath>
#include <sstream>

#include "common/config.h"

namespace minenav {

std::string ValidateOdometryErrorOptions(const OdometryErrorOptions& o) {
  std::ostringstream why;
  const double all[] = {o.scale_error, o.rotation_scale_error, o.heading_drift_per_metre,
                        o.heading_drift_per_second, o.translation_noise, o.rotation_noise};
  for (double v : all)
    if (!std::isfinite(v)) return "odometry error parameters must be finite";
  if (o.scale_error <= -1.0) why << "scale_error must be > -1 (got " << o.scale_error << ")";
  else if (o.rotation_scale_error <= -1.0) why << "rotation_scale_error must be > -1 (got " << o.rotation_scale_error << ")";
  else if (o.translation_noise < 0.0) why << "translation_noise must be >= 0 (got " << o.translation_noise << ")";
  else if (o.rotation_noise < 0.0) why << "rotation_noise must be >= 0 (got " << o.rotation_noise << ")";
  return why.str();
}

DeadReckoning::DeadReckoning(const OdometryErrorOptions& options, const Pose2& initial_pose, uint64_t seed)
    : options_(options), pose_(initial_pose), rng_(seed) {}

void DeadReckoning::Apply(double ds, double dtheta, double dt) {
  std::normal_distribution<double> n01(0.0, 1.0);
  const double ns = options_.translation_noise * std::sqrt(std::abs(ds)) * n01(rng_);
  const double nt = options_.rotation_noise * std::sqrt(std::abs(dtheta) + std::abs(ds)) * n01(rng_);
  const double ds_m = ds * (1.0 + options_.scale_error) + ns;
  const double dth_m = dtheta * (1.0 + options_.rotation_scale_error) +
                       options_.heading_drift_per_metre * std::abs(ds) +
                       options_.heading_drift_per_second * dt + nt;
  if (std::abs(ds_m) < 1e-12)
    pose_ = pose_ * Pose2(0.0, 0.0, NormalizeAngle(dth_m));
  else
    pose_ = pose_ * ArcDelta(ds_m, dth_m / ds_m);
  ++seq_;
  last_v_ = dt > 0.0 ? ds_m / dt : 0.0;
  last_omega_ = dt > 0.0 ? dth_m / dt : 0.0;
}

const Pose2& DeadReckoning::AddIncrement(const MotionIncrement& increment) {
  Apply(increment.distance, increment.rotation, increment.dt);
  return pose_;
}

const Pose2& DeadReckoning::AddRelativeMotion(const Pose2& delta, double dt) {
  std::normal_distribution<double> n01(0.0, 1.0);
  const double trans = std::hypot(delta.x, delta.y);
  const double rot1 = trans > 1e-9 ? std::atan2(delta.y, delta.x) : 0.0;
  const double rot2 = NormalizeAngle(delta.theta - rot1);
  const double rs = options_.rotation_scale_error, rn = options_.rotation_noise;
  const double trans_m = trans * (1.0 + options_.scale_error) +
                         options_.translation_noise * std::sqrt(trans) * n01(rng_);
  const double rot1_m = rot1 * (1.0 + rs) + rn * std::sqrt(std::abs(rot1)) * n01(rng_);
  const double rot2_m = rot2 * (1.0 + rs) + rn * std::sqrt(std::abs(rot2) + trans) * n01(rng_) +
                        options_.heading_drift_per_metre * trans + options_.heading_drift_per_second * dt;
  pose_ = pose_ * Pose2(0.0, 0.0, NormalizeAngle(rot1_m)) * Pose2(trans_m, 0.0, 0.0) *
          Pose2(0.0, 0.0, NormalizeAngle(rot2_m));
  ++seq_;
  last_v_ = dt > 0.0 ? trans_m / dt : 0.0;
  last_omega_ = dt > 0.0 ? (rot1_m + rot2_m) / dt : 0.0;
  return pose_;
}

OdometryReading DeadReckoning::Reading(int64_t utime) const {
  OdometryReading r;
  r.utime = utime;
  r.seq = seq_;
  r.pose = pose_;
  r.v = last_v_;
  r.omega = last_omega_;
  return r;
}

std::vector<Pose2> DeadReckonAlong(const std::vector<Pose2>& truth, const std::vector<double>& times_s,
                                   const OdometryErrorOptions& options, uint64_t seed) {
  std::vector<Pose2> out;
  if (truth.empty()) return out;
  DeadReckoning dr(options, truth.front(), seed);
  out.push_back(truth.front());
  for (size_t i = 1; i < truth.size(); ++i) {
    const double dt = times_s.size() == truth.size() ? times_s[i] - times_s[i - 1] : 1.0;
    out.push_back(dr.AddRelativeMotion(Between(truth[i - 1], truth[i]), dt));
  }
  return out;
}

std::vector<Pose2> PerturbPoses(const std::vector<Pose2>& truth, const PoseNoise& noise, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  std::vector<Pose2> out;
  out.reserve(truth.size());
  for (const Pose2& t : truth) {
    const double dx = noise.sigma_x * n01(rng);
    const double dy = noise.sigma_y * n01(rng);
    const double dth = noise.sigma_theta * n01(rng);
    out.emplace_back(t.x + dx, t.y + dy, NormalizeAngle(t.theta + dth));
  }
  return out;
}

void DeclareOptions(OptionScope scope, OdometryErrorOptions& o) {
  scope.AddDouble("scale_error", &o.scale_error, "fraction",
                  "odometry distance error: 0.02 = reads 2% long (track slip on coal)", -0.5, 0.5);
  scope.AddDouble("rotation_scale_error", &o.rotation_scale_error, "fraction", "error of each heading change",
                  -0.5, 0.5);
  scope.AddDouble("heading_drift_per_metre", &o.heading_drift_per_metre, "rad/m",
                  "heading drift per metre travelled (signed: + drifts counter-clockwise)", -1.0, 1.0);
  scope.AddDouble("heading_drift_per_second", &o.heading_drift_per_second, "rad/s",
                  "heading drift per second, also standing still (a gyro's bias)", -1.0, 1.0);
  scope.AddDouble("translation_noise", &o.translation_noise, "m/sqrt(m)",
                  "std of the distance error after 1 m: a random walk, so the step size does not matter", 0.0, 1.0);
  scope.AddDouble("rotation_noise", &o.rotation_noise, "rad/sqrt(rad)",
                  "std of the heading error after 1 rad (or 1 m) of motion", 0.0, 1.0);
}

}  // namespace minenav
