#pragma once
// The tracker's pose between estimates (thesis 6.4.2: poses every few seconds, odometry in
// between): the latest trusted estimate composed with the odometry since its time, by the
// fleet's one rule (common/odometry_chain.h). Plain C++, no clock.
//
// An estimate is gated before it is trusted. Its residual r = estimate - prediction (at the
// estimate's own time, from the odometry interpolated there) is weighed by the estimate's
// covariance plus the prediction's, m = sqrt(r' (P_est + P_pred)^-1 r) (a Mahalanobis
// distance, in sigmas). The prediction's covariance is the anchor estimate's, grown with the
// odometry's path length since it (a random walk: variance odometry_sigma^2 per metre, plus
// the relative error squared times the distance squared, plus the heading's error times the
// distance for position; the heading's variance grows with the rotation as well).
// Policy (the "pose jump" reaction):
//   * m <= gate_sigma: trusted (the new anchor);
//   * m >  gate_sigma: a jump, reported (EstimateVerdict::jump, the reason in words) and NOT
//     used: the tracker keeps driving on the prediction, and the pose watchdog, which counts
//     only trusted estimates, stops the vehicle when no trusted one comes for its limit;
//   * reanchor_after consecutive jumps that agree with each other (each within gate_sigma of
//     the previous one moved by the odometry since) are trusted: the estimator is consistently
//     elsewhere, so the odometry slipped; reported as a re-anchoring;
//   * an estimate that did not converge, or older than the anchor, is ignored (reported).
// The first estimate is trusted as it is (there is nothing to compare it with).

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>

#include "common/odometry_chain.h"
#include "common/pose2.h"
#include "common/pose_estimate.h"
#include "common/vehicle_state.h"

namespace minenav {

struct PosePredictorOptions {
  double gate_sigma = 4.0;             // sigmas (Mahalanobis) beyond which an estimate is a jump
  int reanchor_after = 3;              // consecutive, mutually consistent jumps then trusted (0 = never)
  double default_sigma_xy = 0.05;      // m, an estimate's position sigma when it carries no covariance
  double default_sigma_theta = 0.01;   // rad, its heading sigma then
  double odometry_sigma = 0.02;        // m/sqrt(m), random-walk position error of the odometry
  double odometry_heading_sigma = 0.01;  // rad/sqrt(m), random-walk heading error of the odometry
  double odometry_relative_error = 0.02; // fraction of the distance: systematic scale error
  double odometry_rotation_error = 0.02; // fraction of the heading turned: systematic rotation error
  double max_odometry_gap = 0.5;       // s, odometry interpolated at an estimate's time across at most this
  double history = 60.0;               // s of odometry kept to find the odometry at an estimate's time
};

std::string ValidatePosePredictorOptions(const PosePredictorOptions& o);
class OptionScope;
void DeclareOptions(OptionScope scope, PosePredictorOptions& o);

struct EstimateVerdict {
  bool trusted = false;
  bool jump = false;        // outside the gate (reported, not obeyed)
  bool reanchored = false;  // trusted after reanchor_after consistent jumps
  double sigmas = 0.0;      // Mahalanobis distance from the prediction (0 for the first)
  std::string reason;       // one line
};

class PosePredictor {
 public:
  explicit PosePredictor(PosePredictorOptions options = {});

  // Odometry readings in time order; an older or equal stamp is ignored (false). A reading
  // that reaches a waiting estimate's time decides it (TakeDeferredVerdict).
  bool AddOdometry(const OdometryReading& reading);
  // An estimate stamped after the latest odometry waits for the odometry of its time (one
  // waits at most: a newer one replaces it); the verdict then says "waiting".
  EstimateVerdict AddEstimate(const PoseEstimate& estimate);
  // The verdict on the waiting estimate, once odometry decided it (then cleared).
  std::optional<EstimateVerdict> TakeDeferredVerdict();

  // The latest estimate composed with the odometry since; nullopt before the first trusted
  // estimate or the first odometry.
  std::optional<Pose2> Predict() const;
  // Covariance of Predict() (x, y, theta).
  Eigen::Matrix3d PredictionCovariance() const;

  std::optional<int64_t> last_trusted_utime() const { return last_trusted_utime_; }
  std::optional<int64_t> last_odometry_utime() const {
    return odometry_.empty() ? std::nullopt : std::optional<int64_t>(odometry_.back().utime);
  }
  int jumps() const { return jumps_total_; }
  const PosePredictorOptions& options() const { return options_; }

 private:
  struct Stamped {
    int64_t utime = 0;
    Pose2 pose;
    double distance = 0.0;  // m of odometry path length since the first reading kept
    double rotation = 0.0;  // rad of heading turned (absolute) since then
  };
  std::optional<Stamped> OdometryAt(int64_t utime) const;
  Eigen::Matrix3d EstimateCovariance(const PoseEstimate& e) const;
  // The growth of the covariance over `distance` m and `rotation` rad of odometry from a pose
  // with the given heading variance.
  Eigen::Matrix3d Growth(double distance, double rotation, double heading_variance) const;
  double Sigmas(const Pose2& a, const Pose2& b, const Eigen::Matrix3d& covariance) const;

  PosePredictorOptions options_;
  std::deque<Stamped> odometry_;
  OdometryChain chain_;
  Eigen::Matrix3d anchor_covariance_ = Eigen::Matrix3d::Zero();
  double anchor_distance_ = 0.0;  // odometry distance at the anchor
  double anchor_rotation_ = 0.0;  // odometry rotation at the anchor
  std::optional<int64_t> last_trusted_utime_;
  // The last jump (for the consistency of consecutive jumps).
  struct Jump {
    Pose2 estimate;
    Eigen::Matrix3d covariance;
    Stamped odometry;
  };
  std::optional<Jump> last_jump_;
  std::optional<PoseEstimate> waiting_;
  std::optional<EstimateVerdict> deferred_;
  int consistent_jumps_ = 0;
  int jumps_total_ = 0;
};

}  // namespace minenav
