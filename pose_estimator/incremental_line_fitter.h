#pragma once
// Total-least-squares line fit over a window of points that can grow and shrink one point
// at a time (thesis 2.1.4: the corner operator slides along the scan, so each arm's fit is
// updated by adding the point entering and removing the point leaving its window instead
// of refitting from scratch). Sums are kept relative to a local origin so that removing
// points does not cancel large numbers.
#include <Eigen/Core>

namespace minenav {

struct LineFit {
  bool valid = false;               // at least two distinct points
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  // unit, along the line
  double rms = 0.0;                 // m, RMS perpendicular distance of the points
  int count = 0;
};

class IncrementalLineFitter {
 public:
  explicit IncrementalLineFitter(const Eigen::Vector2d& origin = Eigen::Vector2d::Zero())
      : origin_(origin) {}

  void Add(const Eigen::Vector2d& p);
  void Remove(const Eigen::Vector2d& p);
  void Clear();
  int count() const { return n_; }
  LineFit Fit() const;

 private:
  Eigen::Vector2d origin_;
  int n_ = 0;
  double sx_ = 0.0, sy_ = 0.0, sxx_ = 0.0, sxy_ = 0.0, syy_ = 0.0;
};

}  // namespace minenav
