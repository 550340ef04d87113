#include "pose_estimator/iconic/multi_scan_matcher.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <sstream>

#include "common/config.h"

#include "pose_estimator/iconic/iconic_residual.h"
#include "pose_estimator/iconic/lookup_table_correspondence.h"
#include "pose_estimator/iconic/scan_set_map.h"

namespace minenav {

namespace {

struct ScanModel {
  std::vector<Eigen::Vector2d> points;
  std::unique_ptr<LookupTableCorrespondence> table;  // raw polylines, own frame
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // bounding circle, own frame
  double radius = 0.0;
  int variable = -1;  // block index among adjustable scans, -1 if fixed
};

double Median(std::vector<double>* v) {
  if (v->empty()) return 0.0;
  auto mid = v->begin() + static_cast<std::ptrdiff_t>(v->size() / 2);
  std::nth_element(v->begin(), mid, v->end());
  return *mid;
}

struct Linearisation {
  std::map<std::pair<int, int>, Eigen::Matrix3d> blocks;  // upper triangle (row <= col)
  Eigen::VectorXd g;
  std::vector<int> matched_per_scan;
  std::vector<double> distances;
  double sum_sq = 0.0, weighted_sq = 0.0;
  int count = 0;
};

Linearisation Linearise(const std::vector<ScanModel>& models, const std::vector<Pose2>& poses,
                        const std::vector<std::vector<int>>& partners, int num_variables, double threshold,
                        const MultiScanOptions& options) {
  Linearisation lin;
  lin.g = Eigen::VectorXd::Zero(3 * num_variables);
  lin.matched_per_scan.assign(models.size(), 0);
  std::vector<Pose2> inverses;
  for (const Pose2& p : poses) inverses.push_back(p.inverse());
  // Only the upper triangle is stored; Eigen matrices start uninitialised, hence Zero().
  auto add_block = [&](int r, int c, const Eigen::Matrix3d& b) {
    auto [it, inserted] = lin.blocks.try_emplace({std::min(r, c), std::max(r, c)}, Eigen::Matrix3d::Zero());
    if (r > c)
      it->second += b.transpose();
    else
      it->second += b;
  };
  for (size_t m = 0; m < models.size(); ++m) {
    const int vm = models[m].variable;
    Eigen::Matrix3d Hmm = Eigen::Matrix3d::Zero();
    std::map<int, std::pair<Eigen::Matrix3d, Eigen::Matrix3d>> cross;  // n -> (Hmn, Hnn)
    const Eigen::Matrix2d Rm = poses[m].rotation();
    const Eigen::Vector2d tm = poses[m].translation();
    for (size_t i = 0; i < models[m].points.size(); i += static_cast<size_t>(options.point_stride)) {
      const Eigen::Vector2d& p = models[m].points[i];
      const Eigen::Vector2d P = Rm * p + tm;
      // One residual for a point and a segment of scan n (A.3).
      bool counted = false;
      auto add = [&](int n, const SegmentMatch& match) {
        const ScanModel& model_n = models[static_cast<size_t>(n)];
        if (options.match.reject_open_ends && IsOpenEnd(model_n.table->open_ends(), match.segment, match.region))
          return;
        const IconicResidual r =
            ComputeIconicResidual(poses[m], p, poses[static_cast<size_t>(n)],
                                  model_n.table->segments()[static_cast<size_t>(match.segment)], match.region);
        const double w = RobustWeight(options.match.loss, r.f, options.match.loss_scale);
        const int vn = model_n.variable;
        if (vm >= 0) {
          Hmm.noalias() += w * r.d_pose_m.transpose() * r.d_pose_m;
          lin.g.segment<3>(3 * vm).noalias() += w * r.f * r.d_pose_m.transpose();
        }
        if (vn >= 0) {
          auto [it, inserted] = cross.try_emplace(n, Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero());
          if (vm >= 0) it->second.first.noalias() += w * r.d_pose_m.transpose() * r.d_pose_n;
          it->second.second.noalias() += w * r.d_pose_n.transpose() * r.d_pose_n;
          lin.g.segment<3>(3 * vn).noalias() += w * r.f * r.d_pose_n.transpose();
        }
        lin.sum_sq += r.f * r.f;
        lin.weighted_sq += w * r.f * r.f;
        ++lin.count;
        lin.distances.push_back(match.distance);
        if (!counted) ++lin.matched_per_scan[m];
        counted = true;
      };
      SegmentMatch best;
      int best_n = -1;
      double best_d = threshold;
      for (int n : partners[m]) {
        if (models[static_cast<size_t>(n)].variable < 0 && vm < 0) continue;
        const Eigen::Vector2d pn = inverses[static_cast<size_t>(n)] * P;
        const double limit = options.every_overlapping_scan ? threshold : best_d;
        if ((pn - models[static_cast<size_t>(n)].centre).norm() > models[static_cast<size_t>(n)].radius + limit)
          continue;
        const SegmentMatch local = models[static_cast<size_t>(n)].table->Nearest(pn, limit);
        if (!local.matched()) continue;
        if (options.every_overlapping_scan) {
          add(n, local);
        } else if (best_n < 0 || local.distance < best.distance) {
          best = local;
          best_n = n;
          best_d = local.distance;
        }
      }
      if (best_n >= 0) add(best_n, best);
    }
    if (vm >= 0) add_block(vm, vm, Hmm);
    for (const auto& [n, hh] : cross) {
      const int vn = models[static_cast<size_t>(n)].variable;
      if (vm >= 0) add_block(vm, vn, hh.first);
      add_block(vn, vn, hh.second);
    }
  }
  return lin;
}

Eigen::SparseMatrix<double> Assemble(const Linearisation& lin, int num_variables) {
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(lin.blocks.size() * 9);
  for (const auto& [rc, b] : lin.blocks) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const int row = 3 * rc.first + i, col = 3 * rc.second + j;
        if (row <= col) triplets.emplace_back(row, col, b(i, j));
      }
  }
  Eigen::SparseMatrix<double> H(3 * num_variables, 3 * num_variables);
  H.setFromTriplets(triplets.begin(), triplets.end());
  return H;  // upper triangle; solvers are told so
}

}  // namespace

MultiScanResult MatchScansSimultaneously(const std::vector<MultiScanInput>& scans, const MultiScanOptions& options) {
  MultiScanResult result;
  for (const MultiScanInput& s : scans) result.poses.push_back(s.initial);
  result.covariances.assign(scans.size(), Eigen::Matrix3d::Zero());
  result.inliers.assign(scans.size(), 0);
  if (const std::string bad = ValidateIconicMatchOptions(options.match); !bad.empty()) {
    result.status = "bad options: " + bad;
    return result;
  }
  if (options.point_stride < 1) {
    result.status = "bad options: point_stride must be >= 1";
    return result;
  }
  if (scans.size() < 2) {
    result.status = "need at least 2 scans, got " + std::to_string(scans.size());
    return result;
  }
  if (std::none_of(scans.begin(), scans.end(), [](const MultiScanInput& s) { return s.fixed; })) {
    result.status = "no scan is fixed: at least one pose must stay put (A.3)";
    return result;
  }

  // Models: points, raw polylines and their tables, in each scan's own frame.
  std::vector<ScanModel> models(scans.size());
  int num_variables = 0;
  for (size_t k = 0; k < scans.size(); ++k) {
    ScanModel& model = models[k];
    for (const Eigen::Vector2d& p : scans[k].points)
      if (std::isfinite(p.x()) && std::isfinite(p.y())) model.points.push_back(p);
    const Pose2& init = scans[k].initial;
    if (!std::isfinite(init.x) || !std::isfinite(init.y) || !std::isfinite(init.theta)) {
      result.status = "scan " + std::to_string(k) + ": initial pose is not finite";
      return result;
    }
    const auto partial = SplitIntoPartialScans(model.points, options.partial);
    std::vector<Segment> segments = PartialScansToSegments(partial);
    std::tie(model.centre, model.radius) = BoundingCircle(segments);
    const double cell = options.cell_size > 0.0 ? options.cell_size : ChooseCellSize(segments);
    model.table = std::make_unique<LookupTableCorrespondence>(std::move(segments), cell,
                                                              options.match.initial_threshold);
    model.variable = scans[k].fixed ? -1 : num_variables++;
  }
  if (num_variables == 0) {
    result.status = "ok";
    result.converged = true;
    return result;
  }
  // Candidate partners: scans near enough to overlap at the initial poses.
  std::vector<std::vector<int>> partners(scans.size());
  for (size_t m = 0; m < scans.size(); ++m)
    for (size_t n = 0; n < scans.size(); ++n)
      if (m != n && TranslationDistance(scans[m].initial, scans[n].initial) <= options.max_pair_distance &&
          !models[n].table->segments().empty())
        partners[m].push_back(static_cast<int>(n));

  std::vector<Pose2> poses = result.poses;
  double threshold = options.match.initial_threshold;
  bool converged = false;
  int iteration = 0;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper> solver;
  auto check_support = [&](const Linearisation& lin) -> std::string {
    for (size_t k = 0; k < models.size(); ++k) {
      if (models[k].variable >= 0 && lin.matched_per_scan[k] < options.match.min_correspondences) {
        std::ostringstream why;
        why << "scan " << k << " has only " << lin.matched_per_scan[k] << " points within " << threshold
            << " m of the other scans (need " << options.match.min_correspondences << ")";
        return why.str();
      }
    }
    return "";
  };
  while (iteration < options.match.max_iterations) {
    ++iteration;
    Linearisation lin = Linearise(models, poses, partners, num_variables, threshold, options);
    if (const std::string why = check_support(lin); !why.empty()) {
      result.status = why;
      result.iterations = iteration;
      return result;
    }
    const auto t0 = std::chrono::steady_clock::now();
    const Eigen::SparseMatrix<double> H = Assemble(lin, num_variables);
    solver.compute(H);
    Eigen::VectorXd D;
    if (solver.info() == Eigen::Success) D = solver.solve(lin.g);
    result.solve_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (solver.info() != Eigen::Success || !D.allFinite() || (solver.vectorD().array() <= 0.0).any()) {
      result.status = "normal equations are singular: some scan is not tied to a fixed scan";
      result.iterations = iteration;
      return result;
    }
    double max_t = 0.0, max_r = 0.0;
    for (size_t k = 0; k < models.size(); ++k) {
      const int v = models[k].variable;
      if (v < 0) continue;
      Eigen::Vector3d d = D.segment<3>(3 * v);
      const double step = std::hypot(d(0), d(1));
      if (step > options.match.max_step_translation) d.head<2>() *= options.match.max_step_translation / step;
      d(2) = std::clamp(d(2), -options.match.max_step_rotation, options.match.max_step_rotation);
      poses[k] = Pose2(poses[k].x - d(0), poses[k].y - d(1), NormalizeAngle(poses[k].theta - d(2)));
      max_t = std::max({max_t, std::abs(d(0)), std::abs(d(1))});
      max_r = std::max(max_r, std::abs(d(2)));
    }
    threshold = std::min(threshold, std::max(Median(&lin.distances), options.match.min_threshold));
    if (max_t < options.epsilon_translation && max_r < options.epsilon_rotation) {
      converged = true;
      break;
    }
  }

  // Final statistics and marginal covariances at the final poses.
  Linearisation lin = Linearise(models, poses, partners, num_variables, threshold, options);
  result.poses = poses;
  result.iterations = iteration;
  result.final_threshold = threshold;
  result.num_inliers = lin.count;
  result.inliers = lin.matched_per_scan;
  result.residual = lin.count > 0 ? std::sqrt(lin.sum_sq / lin.count) : 0.0;
  solver.compute(Assemble(lin, num_variables));
  if (solver.info() != Eigen::Success) {
    result.status = "normal equations are singular at the final poses";
    return result;
  }
  const double sigma2 = lin.weighted_sq / std::max(1, lin.count - 3 * num_variables);
  for (size_t k = 0; k < models.size(); ++k) {
    const int v = models[k].variable;
    if (v < 0) continue;
    Eigen::MatrixXd E = Eigen::MatrixXd::Zero(3 * num_variables, 3);
    E.block<3, 3>(3 * v, 0).setIdentity();
    const Eigen::MatrixXd X = solver.solve(E);
    result.covariances[k] = sigma2 * X.block<3, 3>(3 * v, 0);
  }
  if (!converged) {
    result.status = "no convergence in " + std::to_string(options.match.max_iterations) + " iterations";
    return result;
  }
  result.converged = true;
  result.status = "ok";
  return result;
}

void DeclareMultiScanParameters(OptionScope scope, const MultiScanParameters& p) {
  scope.AddDouble("epsilon_translation", p.epsilon_translation, "m",
                  "converged when no pose moves more: looser than one scan's, since points hop between "
                  "overlapping scans' polylines and the step jitters at ~0.3 mm (1 mm)",
                  1e-9, 1.0);
  scope.AddDouble("epsilon_rotation", p.epsilon_rotation, "rad",
                  "converged when no heading moves more (1e-4 rad, for the same reason)", 1e-12, 1.0);
  scope.AddDouble("max_pair_distance", p.max_pair_distance, "m",
                  "scans whose initial positions are farther apart are never paired: beyond twice the useful "
                  "range two scans cannot overlap (60 m)",
                  0.0, 1e6);
  scope.AddBool("every_overlapping_scan", p.every_overlapping_scan,
                "a residual for every other scan with a segment within the threshold (A.3) rather than only for "
                "the nearest: picking the nearest of several noisy polylines biases each link by ~1 cm");
  scope.AddInt("point_stride", p.point_stride, "every k-th point of a scan is a query (1 = all)", 1, 1000);
}

void DeclareOptions(OptionScope scope, MultiScanOptions& o) {
  DeclareOptions(scope.Nested("match"), o.match);
  DeclareMultiScanParameters(scope, {&o.epsilon_translation, &o.epsilon_rotation, &o.max_pair_distance,
                                     &o.every_overlapping_scan, &o.point_stride});
  DeclareOptions(scope.Nested("partial"), o.partial);
  scope.AddDouble("cell_size", &o.cell_size, "m",
                  "lookup table cell of each scan's table: raw scan segments are a few cm long, and the automatic "
                  "(0, finer) size makes queries faster but builds much slower (0.1 m)",
                  0.0, 10.0);
}

}  // namespace minenav
