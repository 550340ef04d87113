#pragma once
// Chaining odometry between scans: the initial estimate of a scan is the last trusted
// estimate moved by the odometry measured since it,
//   initial = estimate_k ⊕ (odometry_k ⊖ odometry_now) = estimate_k · odometry_k⁻¹ · odometry_now,
// so only the odometry's drift since the last trusted pose carries into the guess (thesis
// 6.4.2: poses every few seconds, odometry in between). Before any trusted estimate the
// odometry pose itself is the guess. The pose estimators, the contour mapper and (later)
// the path tracker's prediction use this one rule.

#include <optional>

#include "common/pose2.h"

namespace minenav {

class OdometryChain {
 public:
  struct Anchor {
    Pose2 estimate;  // trusted pose in the map frame
    Pose2 odometry;  // odometry pose at the same time
  };

  // The chained guess for a scan whose odometry pose is `odometry`.
  Pose2 Predict(const Pose2& odometry) const {
    return anchor_ ? anchor_->estimate * Between(anchor_->odometry, odometry) : odometry;
  }
  // A trusted estimate and the odometry at its time become the new anchor.
  void Trust(const Pose2& estimate, const Pose2& odometry) { anchor_ = Anchor{estimate, odometry}; }
  void Reset() { anchor_.reset(); }

  bool anchored() const { return anchor_.has_value(); }
  const std::optional<Anchor>& anchor() const { return anchor_; }

 private:
  std::optional<Anchor> anchor_;
};

}  // namespace minenav
