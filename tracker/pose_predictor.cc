#include "tracker/pose_predictor.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/angle.h"
#include "common/config.h"
#include "common/pose_at_time.h"

namespace minenav {

std::string ValidatePosePredictorOptions(const PosePredictorOptions& o) {
  if (!(o.gate_sigma > 0.0)) return "gate_sigma must be > 0";
  if (o.reanchor_after < 0) return "reanchor_after must be >= 0";
  if (!(o.default_sigma_xy > 0.0) || !(o.default_sigma_theta > 0.0))
    return "default_sigma_xy and default_sigma_theta must be > 0";
  if (o.odometry_sigma < 0.0 || o.odometry_heading_sigma < 0.0 || o.odometry_relative_error < 0.0 ||
      o.odometry_rotation_error < 0.0)
    return "the odometry error model must not be negative";
  if (o.history < o.max_odometry_gap) return "history must be at least max_odometry_gap";
  return "";
}

void DeclareOptions(OptionScope s, PosePredictorOptions& o) {
  s.AddDouble("gate_sigma", &o.gate_sigma, "sigma",
              "Mahalanobis distance from the prediction beyond which an estimate is a jump (reported, not used)", 0.1,
              1000.0);
  s.AddInt("reanchor_after", &o.reanchor_after,
           "consecutive jumps that agree with each other, then trusted (the odometry slipped); 0 = never", 0, 1000);
  s.AddDouble("default_sigma_xy", &o.default_sigma_xy, "m", "position sigma of an estimate without covariance", 1e-4,
              100.0);
  s.AddDouble("default_sigma_theta", &o.default_sigma_theta, "rad", "heading sigma of an estimate without covariance",
              1e-5, 10.0);
  s.AddDouble("odometry_sigma", &o.odometry_sigma, "m/sqrt(m)", "random-walk position error of the odometry", 0.0,
              10.0);
  s.AddDouble("odometry_heading_sigma", &o.odometry_heading_sigma, "rad/sqrt(m)",
              "random-walk heading error of the odometry", 0.0, 10.0);
  s.AddDouble("odometry_relative_error", &o.odometry_relative_error, "",
              "systematic odometry error as a fraction of the distance travelled", 0.0, 1.0);
  s.AddDouble("odometry_rotation_error", &o.odometry_rotation_error, "",
              "systematic odometry error as a fraction of the heading turned", 0.0, 1.0);
  s.AddDouble("max_odometry_gap", &o.max_odometry_gap, "s",
              "odometry is interpolated at an estimate's time across at most this gap", 0.001, 60.0);
  s.AddDouble("history", &o.history, "s", "odometry kept to find the odometry at an estimate's time", 0.01, 3600.0);
}

PosePredictor::PosePredictor(PosePredictorOptions options) : options_(options) {}

bool PosePredictor::AddOdometry(const OdometryReading& r) {
  if (!odometry_.empty() && r.utime <= odometry_.back().utime) return false;
  Stamped s{r.utime, r.pose, 0.0, 0.0};
  if (!odometry_.empty()) {
    s.distance = odometry_.back().distance + TranslationDistance(odometry_.back().pose, r.pose);
    s.rotation = odometry_.back().rotation + HeadingDistance(odometry_.back().pose, r.pose);
  }
  odometry_.push_back(s);
  const auto keep = static_cast<int64_t>(options_.history * 1e6);
  while (odometry_.size() > 2 && TimeGap(r.utime, odometry_.front().utime) > static_cast<uint64_t>(keep))
    odometry_.pop_front();
  if (waiting_ && r.utime >= waiting_->utime) {
    const PoseEstimate e = *waiting_;
    waiting_.reset();
    deferred_ = AddEstimate(e);
  }
  return true;
}

std::optional<EstimateVerdict> PosePredictor::TakeDeferredVerdict() {
  std::optional<EstimateVerdict> v = std::move(deferred_);
  deferred_.reset();
  return v;
}

std::optional<PosePredictor::Stamped> PosePredictor::OdometryAt(int64_t utime) const {
  const auto gap = static_cast<int64_t>(options_.max_odometry_gap * 1e6);
  const std::optional<Pose2> pose = PoseAtTime(odometry_, utime, gap);
  if (!pose) return std::nullopt;
  // The distance at that time: nearest reading's (the interpolation's error is sub-mm).
  const auto it = std::lower_bound(odometry_.begin(), odometry_.end(), utime,
                                   [](const Stamped& s, int64_t t) { return s.utime < t; });
  const Stamped& near = it == odometry_.end() ? odometry_.back() : *it;
  return Stamped{utime, *pose, near.distance, near.rotation};
}

Eigen::Matrix3d PosePredictor::EstimateCovariance(const PoseEstimate& e) const {
  const Eigen::Matrix3d& c = e.covariance;
  if (c.allFinite() && c.diagonal().minCoeff() > 0.0) return c;
  Eigen::Matrix3d d = Eigen::Matrix3d::Zero();
  d(0, 0) = d(1, 1) = options_.default_sigma_xy * options_.default_sigma_xy;
  d(2, 2) = options_.default_sigma_theta * options_.default_sigma_theta;
  return d;
}

Eigen::Matrix3d PosePredictor::Growth(double distance, double rotation, double heading_variance) const {
  const double s = std::max(0.0, distance), turned = std::max(0.0, rotation);
  const double rot = options_.odometry_rotation_error * turned;
  Eigen::Matrix3d g = Eigen::Matrix3d::Zero();
  const double rel = options_.odometry_relative_error * s;
  g(0, 0) = g(1, 1) = options_.odometry_sigma * options_.odometry_sigma * s + rel * rel + heading_variance * s * s;
  g(2, 2) = options_.odometry_heading_sigma * options_.odometry_heading_sigma * (s + turned) + rot * rot;
  return g;
}

double PosePredictor::Sigmas(const Pose2& a, const Pose2& b, const Eigen::Matrix3d& covariance) const {
  const Eigen::Vector3d r(a.x - b.x, a.y - b.y, NormalizeAngle(a.theta - b.theta));
  const Eigen::Matrix3d c = covariance + 1e-12 * Eigen::Matrix3d::Identity();
  const double m2 = r.dot(c.ldlt().solve(r));
  return std::sqrt(std::max(0.0, m2));
}

EstimateVerdict PosePredictor::AddEstimate(const PoseEstimate& e) {
  EstimateVerdict v;
  if (!e.converged) {
    v.reason = "estimate not converged (" + e.status + "): ignored";
    return v;
  }
  if (last_trusted_utime_ && e.utime <= *last_trusted_utime_) {
    v.reason = "estimate older than the last trusted one: ignored";
    return v;
  }
  if (odometry_.empty() || e.utime > odometry_.back().utime) {
    waiting_ = e;
    v.reason = "waiting for the odometry of the estimate's time";
    return v;
  }
  const std::optional<Stamped> odo = OdometryAt(e.utime);
  if (!odo) {
    v.reason = "no odometry within " + std::to_string(options_.max_odometry_gap) + " s of the estimate's time: ignored";
    return v;
  }
  const Eigen::Matrix3d pe = EstimateCovariance(e);
  auto trust = [&](const std::string& why) {
    chain_.Trust(e.pose, odo->pose);
    anchor_covariance_ = pe;
    anchor_distance_ = odo->distance;
    anchor_rotation_ = odo->rotation;
    last_trusted_utime_ = e.utime;
    last_jump_.reset();
    consistent_jumps_ = 0;
    v.trusted = true;
    v.reason = why;
  };
  if (!chain_.anchored()) {
    trust("first estimate");
    return v;
  }
  const Pose2 predicted = chain_.Predict(odo->pose);
  const Eigen::Matrix3d pp = anchor_covariance_ + Growth(odo->distance - anchor_distance_, odo->rotation - anchor_rotation_, anchor_covariance_(2, 2));
  v.sigmas = Sigmas(e.pose, predicted, pe + pp);
  std::ostringstream os;
  os.precision(3);
  if (v.sigmas <= options_.gate_sigma) {
    os << "trusted, " << v.sigmas << " sigma from the prediction";
    trust(os.str());
    return v;
  }
  v.jump = true;
  ++jumps_total_;
  // Does it agree with the previous jump, moved by the odometry since?
  if (last_jump_) {
    const Pose2 moved = last_jump_->estimate * Between(last_jump_->odometry.pose, odo->pose);
    const double between = Sigmas(e.pose, moved, pe + last_jump_->covariance +
                                                     Growth(odo->distance - last_jump_->odometry.distance,
                                                            odo->rotation - last_jump_->odometry.rotation,
                                                            last_jump_->covariance(2, 2)));
    consistent_jumps_ = between <= options_.gate_sigma ? consistent_jumps_ + 1 : 1;
  } else {
    consistent_jumps_ = 1;
  }
  last_jump_ = Jump{e.pose, pe, *odo};
  os << "pose jump: estimate " << e.pose << " is " << v.sigmas << " sigma from the prediction " << predicted
     << " (gate " << options_.gate_sigma << ")";
  if (options_.reanchor_after > 0 && consistent_jumps_ >= options_.reanchor_after) {
    const std::string what = os.str();
    trust(what + "; re-anchored after " + std::to_string(consistent_jumps_) + " consistent estimates");
    v.reanchored = true;
    return v;
  }
  os << "; not used";
  v.reason = os.str();
  return v;
}

std::optional<Pose2> PosePredictor::Predict() const {
  if (!chain_.anchored() || odometry_.empty()) return std::nullopt;
  return chain_.Predict(odometry_.back().pose);
}

Eigen::Matrix3d PosePredictor::PredictionCovariance() const {
  if (odometry_.empty()) return anchor_covariance_;
  return anchor_covariance_ + Growth(odometry_.back().distance - anchor_distance_,
                                     odometry_.back().rotation - anchor_rotation_, anchor_covariance_(2, 2));
}

}  // namespace minenav
