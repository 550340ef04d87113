#include "pose_estimator/feature/corner_operator.h"

#include <algorithm>
#include <cmath>

#include "common/config.h"
#include "pose_estimator/feature/incremental_line_fitter.h"

namespace minenav {
namespace {

// Unit direction of a fit, oriented from `from` toward the fit's centroid.
Eigen::Vector2d Oriented(const LineFit& f, const Eigen::Vector2d& from) {
  return f.direction.dot(f.centroid - from) >= 0.0 ? f.direction : Eigen::Vector2d(-f.direction);
}

// Intersection of two lines given by point and direction; nullopt-like flag if parallel.
bool Intersect(const Eigen::Vector2d& p1, const Eigen::Vector2d& d1, const Eigen::Vector2d& p2,
               const Eigen::Vector2d& d2, Eigen::Vector2d* out) {
  const double den = d1.x() * d2.y() - d1.y() * d2.x();
  if (std::abs(den) < 1e-9) return false;
  const Eigen::Vector2d w = p2 - p1;
  const double t = (w.x() * d2.y() - w.y() * d2.x()) / den;
  *out = p1 + t * d1;
  return true;
}

}  // namespace

std::vector<CornerCandidate> ApplyCornerOperator(const std::vector<Eigen::Vector2d>& piece,
                                                 const CornerOperatorOptions& options) {
  std::vector<CornerCandidate> corners;
  const int m = static_cast<int>(piece.size());
  if (m < 2 * options.min_arm_points - 1) return corners;
  auto at = [&](int i) -> const Eigen::Vector2d& { return piece[static_cast<size_t>(i)]; };
  const double arm = options.arm_length;
  IncrementalLineFitter left(at(0)), right(at(0));
  int lo = 0, hi = 0;
  left.Add(at(0));
  right.Add(at(0));
  while (hi + 1 < m && (at(hi + 1) - at(0)).norm() <= arm) right.Add(at(++hi));

  bool in_run = false;
  CornerCandidate best;
  double best_score = 0.0;
  for (int i = 0; i < m; ++i) {
    if (i > 0) {
      left.Add(at(i));
      while (lo < i && (at(lo) - at(i)).norm() > arm) left.Remove(at(lo++));
      right.Remove(at(i - 1));
      if (hi < i) {
        hi = i;
        right.Add(at(i));
      }
      while (hi + 1 < m && (at(hi + 1) - at(i)).norm() <= arm) right.Add(at(++hi));
    }
    bool candidate = false;
    CornerCandidate c;
    double score = 0.0;
    if (left.count() >= options.min_arm_points && right.count() >= options.min_arm_points &&
        (at(lo) - at(i)).norm() >= options.min_arm_extent * arm &&
        (at(hi) - at(i)).norm() >= options.min_arm_extent * arm) {
      const LineFit fl = left.Fit(), fr = right.Fit();
      if (fl.valid && fr.valid && fl.rms <= options.max_arm_rms && fr.rms <= options.max_arm_rms) {
        const Eigen::Vector2d ul = Oriented(fl, at(i)), ur = Oriented(fr, at(i));
        const double angle = std::acos(std::clamp(ul.dot(ur), -1.0, 1.0));
        Eigen::Vector2d vertex;
        if (angle >= options.min_corner_angle && angle <= options.max_corner_angle &&
            Intersect(fl.centroid, fl.direction, fr.centroid, fr.direction, &vertex)) {
          candidate = true;
          const double nl = fl.count, nr = fr.count;
          score = (nl * fl.rms * fl.rms + nr * fr.rms * fr.rms) / (nl + nr);
          c.index = i;
          c.vertex = vertex;
          // Re-orient the arms from the vertex itself, which may lie off the centre point.
          c.arm_before = Oriented(fl, vertex);
          c.arm_after = Oriented(fr, vertex);
          const Eigen::Vector2d ray = vertex.normalized();
          const double min_sin = std::sin(options.min_arm_to_ray_angle);
          if (std::abs(ray.x() * c.arm_before.y() - ray.y() * c.arm_before.x()) < min_sin ||
              std::abs(ray.x() * c.arm_after.y() - ray.y() * c.arm_after.x()) < min_sin) {
            candidate = false;
          }
          c.num_points = fl.count + fr.count - 1;
          c.fit_rms = std::sqrt(score);
        }
      }
    }
    if (candidate) {
      if (!in_run || score < best_score) {
        best = c;
        best_score = score;
      }
      in_run = true;
    } else if (in_run) {
      corners.push_back(best);
      in_run = false;
    }
  }
  if (in_run) corners.push_back(best);
  // Noise can split one corner's run of candidates in two: merge close neighbours.
  std::vector<CornerCandidate> merged;
  for (const CornerCandidate& c : corners) {
    if (!merged.empty() &&
        (merged.back().vertex - c.vertex).norm() < options.min_corner_separation * arm) {
      if (c.fit_rms < merged.back().fit_rms) merged.back() = c;
      continue;
    }
    merged.push_back(c);
  }
  return merged;
}

void DeclareOptions(OptionScope scope, CornerOperatorOptions& o) {
  scope.AddDouble("arm_length", &o.arm_length, "m",
                  "length of each arm of the corner template: long enough to average the range noise, short "
                  "enough to fit between features (0.8 m)",
                  0.05, 10.0);
  scope.AddInt("min_arm_points", &o.min_arm_points, "points an arm needs to be fit (5)", 2, 100000);
  scope.AddDouble("min_arm_extent", &o.min_arm_extent, "1",
                  "fraction of arm_length an arm must span: an arm cut short by a gap is not trusted (0.7)", 0.0,
                  1.0);
  scope.AddDouble("min_corner_angle", &o.min_corner_angle, "rad",
                  "smallest angle between the two arms of a corner: mine corners are 'around 90 degrees' (60 deg)",
                  0.0, 3.2);
  scope.AddDouble("max_corner_angle", &o.max_corner_angle, "rad",
                  "largest angle between the two arms of a corner (120 deg)", 0.0, 3.2);
  scope.AddDouble("max_arm_rms", &o.max_arm_rms, "m",
                  "straightness of each arm: largest RMS of its line fit (0.15 m, ~1.5 sigma of the Cyclone)", 0.001,
                  10.0);
  scope.AddDouble("min_arm_to_ray_angle", &o.min_arm_to_ray_angle, "rad",
                  "an arm closer than this to the ray through the vertex is seen at a grazing angle or is a streak "
                  "of mixed pixels at an occlusion (2.2): no corner there (15 deg)",
                  0.0, 1.6);
  scope.AddDouble("min_corner_separation", &o.min_corner_separation, "1",
                  "corners closer than this fraction of arm_length are one corner, the better fit wins (0.5)", 0.0,
                  10.0);
}

}  // namespace minenav
