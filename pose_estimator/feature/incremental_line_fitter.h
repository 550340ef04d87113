#pragma once
// Total-least-squares line fit over a window of points that can grow and shrink one point
// at a time (thesis 2.1.4: the corner operator slides along the scan, so each arm's fit is
// updated by adding the point entering and removing the point leaving its window instead
// of refitting from scratch). Sums are kept relative to a local origin so that removing
// points does not cancel large numbers.
//
// Range noise lies along the ray, not across the line: on a wall seen obliquely it is
// correlated along and across the wall, and a plain total-least-squares fit turns the line
// toward the rays by about sigma^2 sin(2a) / (2 var_along) (0.4 deg for a 3 m wall at 45
// deg with sigma 10 cm). With ray_sigma > 0 the expected noise scatter,
// sigma^2 * mean(d d^T) for the unit ray directions d (rays from the frame origin: points in
// the sensor frame), is taken out of the scatter matrix before the direction is found.
#include <Eigen/Core>

namespace minenav {

struct LineFit {
  bool valid = false;               // at least two distinct points
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  // unit, along the line
  double rms = 0.0;                 // m, RMS perpendicular distance of the points (uncorrected)
  int count = 0;
};

class IncrementalLineFitter {
 public:
  explicit IncrementalLineFitter(const Eigen::Vector2d& origin = Eigen::Vector2d::Zero(),
                                 double ray_sigma = 0.0)
      : origin_(origin), ray_variance_(ray_sigma * ray_sigma) {}

  void Add(const Eigen::Vector2d& p);
  void Remove(const Eigen::Vector2d& p);
  void Clear();
  int count() const { return n_; }
  LineFit Fit() const;

 private:
  Eigen::Vector2d origin_;
  double ray_variance_ = 0.0;  // m^2
  int n_ = 0;
  double sx_ = 0.0, sy_ = 0.0, sxx_ = 0.0, sxy_ = 0.0, syy_ = 0.0;
  double dxx_ = 0.0, dxy_ = 0.0, dyy_ = 0.0;  // sums of d d^T of the ray directions
};

}  // namespace minenav
