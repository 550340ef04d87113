#include "mapper/contour_fitting.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_map>

#include "mapper/correspondence.h"
#include "mapper/integral_error.h"
#include "mapper/line_search.h"

namespace minenav::mapper {

std::string ValidateOptions(const ContourFittingOptions& o) {
  std::ostringstream why;
  if (!(o.correspondence_threshold > 0.0))
    why << "correspondence_threshold must be > 0 m, got " << o.correspondence_threshold;
  else if (!(o.min_segment_length >= 0.0))
    why << "min_segment_length must be >= 0 m, got " << o.min_segment_length;
  else if (o.max_iterations < 1)
    why << "max_iterations must be >= 1, got " << o.max_iterations;
  else if (!(o.step_resolution > 0.0) || !(o.gradient_tolerance >= 0.0) || !(o.min_vertex_change >= 0.0))
    why << "step_resolution must be > 0, gradient_tolerance and min_vertex_change >= 0";
  else if (!(o.damping > 0.0))
    why << "damping must be > 0, got " << o.damping;
  else if (!(o.min_curvature >= 0.0))
    why << "min_curvature must be >= 0 m, got " << o.min_curvature;
  return why.str();
}

void DeclareOptions(OptionScope s, ContourFittingOptions& o) {
  s.AddDouble("correspondence_threshold", &o.correspondence_threshold, "m",
              "scan-to-contour threshold while fitting; 0.2 m, as map expansion's, so every point that "
              "made a contour pulls on it",
              0.001, 100.0);
  s.AddDouble("min_segment_length", &o.min_segment_length, "m",
              "shorter segments are merged away before each iteration (they make the gradient unstable and let "
              "noise into the contour); 0.1 m",
              0.0, 100.0);
  s.AddDouble("max_turn", &o.max_turn, "rad",
              "a vertex where the contour turns back by more than this is removed (a spike of a noisy rough fit); "
              "2.4 rad (137 degrees) spares real corners",
              0.0, kPi);
  s.AddInt("max_iterations", &o.max_iterations,
           "iteration limit (termination 5); 30: the preconditioned descent converges in a few [iterations]", 1,
           100000);
  s.AddDouble("gradient_tolerance", &o.gradient_tolerance, "m",
              "termination 2: the largest vertex gradient per matched length below this ends the fit; 1e-7 m",
              0.0, 1.0);
  s.AddDouble("step_resolution", &o.step_resolution, "m",
              "line-search resolution, the smallest vertex move searched (termination 3); 1e-4 m", 1e-9,
              1.0);
  s.AddDouble("min_vertex_change", &o.min_vertex_change, "m",
              "termination 4: the largest vertex move of an iteration below this ends the fit; 1e-4 m",
              0.0, 1.0);
  s.AddBool("precondition", &o.precondition,
            "precondition the gradient by each vertex's Gauss-Newton curvature: the thesis's plain "
            "gradient (false) needs hundreds of iterations when vertices see different amounts of data");
  s.AddDouble("damping", &o.damping, "1",
              "damping of the per-vertex curvature, a fraction of its trace, so directions the data do not "
              "constrain (along a straight wall) stay put; 0.05",
              1e-9, 100.0);
  s.AddDouble("min_curvature", &o.min_curvature, "m",
              "added to every vertex's curvature so a vertex touched by a sliver of data takes small steps; 0.02 m, "
              "about 3 % of a vertex seen along both its 0.5 m segments",
              0.0, 100.0);
}

namespace {

struct Box {
  Eigen::Vector2d lo{1e300, 1e300}, hi{-1e300, -1e300};
  void Add(const Eigen::Vector2d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool Overlaps(const Box& o, double margin) const {
    return lo.x() <= o.hi.x() + margin && o.lo.x() <= hi.x() + margin && lo.y() <= o.hi.y() + margin &&
           o.lo.y() <= hi.y() + margin;
  }
};

struct FitPiece {
  Eigen::Vector2d p_i, p_j;  // world
  int vs = 0, ve = 0;        // indices into the flat vertex array
};

// The contours being fitted, their vertices laid out in one array.
struct Problem {
  std::vector<bool> free;  // per vertex: may it move?
  std::vector<int> ids;
  std::unordered_map<int, int> offset;  // contour id -> index of its first vertex
  std::vector<Eigen::Vector2d> x;
  Box box;
};

Problem MakeProblem(const std::vector<int>& ids, const ContourMap& map, const FitRegion* region) {
  Problem p;
  for (const int id : ids) {
    const Contour* c = map.Find(id);
    if (!c || c->NumSegments() < 2 || p.offset.count(id)) continue;
    p.ids.push_back(id);
    p.offset[id] = static_cast<int>(p.x.size());
    for (const auto& v : c->points) {
      const bool free = !region || region->Contains(v);
      p.x.push_back(v);
      p.free.push_back(free);
      if (free) p.box.Add(v);
    }
  }
  return p;
}

// World points of every scan, with a bounding box per partial scan (poses are fixed).
struct WorldScan {
  Eigen::Vector2d sensor;
  std::vector<std::vector<Eigen::Vector2d>> partials;
  std::vector<Box> boxes;
};

std::vector<WorldScan> ToWorldScans(const std::vector<MappedScan>& scans) {
  std::vector<WorldScan> out;
  out.reserve(scans.size());
  for (const MappedScan& s : scans) {
    WorldScan w;
    w.sensor = s.pose * s.scan.sensor_position;
    for (const PartialScan& p : s.scan.partial_scans) {
      w.partials.push_back(ToWorld(p, s.pose));
      Box b;
      for (const auto& q : w.partials.back()) b.Add(q);
      w.boxes.push_back(b);
    }
    out.push_back(std::move(w));
  }
  return out;
}

std::vector<FitPiece> CollectPieces(const Problem& prob, const std::vector<WorldScan>& scans, const ContourMap& map,
                                    double threshold) {
  // Longest segment among the fitted contours: points this far outside the box of the free
  // vertices may still fall on a segment with a free end.
  double max_segment = 0.0;
  for (const int id : prob.ids) {
    const Contour& c = map.Get(id);
    for (int k = 0; k < c.NumSegments(); ++k) max_segment = std::max(max_segment, c.GetSegment(k).length());
  }
  std::vector<FitPiece> out;
  std::vector<ErrorPiece> pieces;
  for (const WorldScan& w : scans)
    for (size_t k = 0; k < w.partials.size(); ++k) {
      if (!w.boxes[k].Overlaps(prob.box, threshold + max_segment)) continue;
      // Only points near the free vertices can matter.
      const auto& all = w.partials[k];
      std::vector<Eigen::Vector2d> pts;
      pts.reserve(all.size());
      const double margin = threshold + max_segment;
      for (const auto& q : all)
        if (q.x() >= prob.box.lo.x() - margin && q.x() <= prob.box.hi.x() + margin &&
            q.y() >= prob.box.lo.y() - margin && q.y() <= prob.box.hi.y() + margin)
          pts.push_back(q);
      pieces.clear();
      AppendPieces(0, MatchPoints(pts, w.sensor, map, threshold), &pieces);
      for (const ErrorPiece& e : pieces) {
        const auto it = prob.offset.find(e.segment.contour);
        if (it == prob.offset.end()) continue;
        const Contour& c = map.Get(e.segment.contour);
        const int vs = it->second + c.SegmentStart(e.segment.segment);
        const int ve = it->second + c.SegmentEnd(e.segment.segment);
        if (!prob.free[static_cast<size_t>(vs)] && !prob.free[static_cast<size_t>(ve)]) continue;
        out.push_back({pts[static_cast<size_t>(e.i)], pts[static_cast<size_t>(e.j)], vs, ve});
      }
    }
  return out;
}

double Error(const std::vector<FitPiece>& pieces, const std::vector<Eigen::Vector2d>& x) {
  double f = 0.0;
  for (const FitPiece& p : pieces)
    f += PieceError(p.p_i, p.p_j, x[static_cast<size_t>(p.vs)], x[static_cast<size_t>(p.ve)]);
  return f;
}

}  // namespace

ContourFittingResult FitContours(const std::vector<int>& ids, const std::vector<MappedScan>& scans, ContourMap& map,
                                 const ContourFittingOptions& o, const FitRegion* region) {
  ContourFittingResult out;
  const std::vector<WorldScan> world = ToWorldScans(scans);
  const double thr = o.correspondence_threshold;
  bool first = true;
  for (int iter = 1; iter <= o.max_iterations; ++iter) {
    out.iterations = iter;
    // 1. Degenerate segments.
    for (const int id : ids)
      if (map.Find(id)) {
        out.vertices_removed += map.RemoveSpikes(id, o.max_turn);
        out.vertices_removed += map.RemoveDegenerateSegments(id, o.min_segment_length);
      }
    Problem prob = MakeProblem(ids, map, region);
    if (prob.ids.empty() || prob.box.lo.x() > prob.box.hi.x()) {
      out.converged = true;
      out.reason = "fewer than 2 segments";
      break;
    }
    // 2. Correspondence.
    const std::vector<FitPiece> pieces = CollectPieces(prob, world, map, thr);
    const double f0 = Error(pieces, prob.x);
    if (first) {
      out.error_before = f0;
      first = false;
    }
    // 3. Gradient (EQ 4) and per-vertex curvature.
    const size_t n = prob.x.size();
    std::vector<Eigen::Vector2d> g(n, Eigen::Vector2d::Zero());
    std::vector<Eigen::Matrix2d> h(n, Eigen::Matrix2d::Zero());
    double length = 0.0;
    for (const FitPiece& p : pieces) {
      const Eigen::Vector2d& s = prob.x[static_cast<size_t>(p.vs)];
      const Eigen::Vector2d& e = prob.x[static_cast<size_t>(p.ve)];
      const PieceGradient pg = PieceErrorGradient(p.p_i, p.p_j, s, e);
      g[static_cast<size_t>(p.vs)] += pg.d_s;
      g[static_cast<size_t>(p.ve)] += pg.d_e;
      const PieceCurvature pc = PieceVertexCurvature(p.p_i, p.p_j, s, e);
      const Eigen::Matrix2d nn = pc.normal * pc.normal.transpose();
      h[static_cast<size_t>(p.vs)] += 2.0 * pc.w_s * nn;
      h[static_cast<size_t>(p.ve)] += 2.0 * pc.w_e * nn;
      if ((e - s).norm() > 0.0) length += std::abs((e - s).normalized().dot(p.p_j - p.p_i));
    }
    double max_g = 0.0;
    for (size_t v = 0; v < n; ++v)
      if (prob.free[v]) max_g = std::max(max_g, g[v].norm());
    if (pieces.empty() || max_g / std::max(length, 1e-9) < o.gradient_tolerance) {
      out.converged = true;
      out.reason = pieces.empty() ? "no correspondences" : "gradient small";
      break;
    }
    std::vector<Eigen::Vector2d> dir(n);
    double max_d = 0.0;
    for (size_t v = 0; v < n; ++v) {
      if (!prob.free[v]) {
        dir[v].setZero();
      } else if (o.precondition) {
        const double mu = o.damping * h[v].trace() + o.min_curvature + 1e-12;
        dir[v] = -(h[v] + mu * Eigen::Matrix2d::Identity()).ldlt().solve(g[v]);
      } else {
        dir[v] = -g[v];
      }
      max_d = std::max(max_d, dir[v].norm());
    }
    if (!(max_d > 0.0) || !std::isfinite(max_d)) {
      out.converged = true;
      out.reason = "gradient small";
      break;
    }
    for (auto& d : dir) d /= max_d;  // λ is now the largest vertex move in metres
    // 4. Line search, bounded by the correspondence threshold (EQ 5).
    std::vector<Eigen::Vector2d> trial(n);
    const LineSearchResult ls = LineSearch(
        [&](double l) {
          for (size_t v = 0; v < n; ++v) trial[v] = prob.x[v] + l * dir[v];
          return Error(pieces, trial);
        },
        f0, thr, o.step_resolution);
    if (ls.lambda < 2.0 * o.step_resolution) {
      out.converged = true;
      out.reason = "step (lambda) small";
      break;
    }
    // 5. Update.
    for (const int id : prob.ids) {
      const int off = prob.offset[id];
      std::vector<Eigen::Vector2d> pts(map.Get(id).points.size());
      for (size_t k = 0; k < pts.size(); ++k) pts[k] = prob.x[static_cast<size_t>(off) + k] + ls.lambda * dir[static_cast<size_t>(off) + k];
      map.SetPoints(id, std::move(pts));
    }
    if (ls.lambda < o.min_vertex_change) {
      out.converged = true;
      out.reason = "vertex change small";
      break;
    }
  }
  if (out.reason.empty()) out.reason = "iteration limit";
  const Problem prob = MakeProblem(ids, map, region);
  if (prob.ids.empty() || prob.box.lo.x() > prob.box.hi.x()) return out;
  const std::vector<FitPiece> pieces = CollectPieces(prob, world, map, thr);
  out.error_after = Error(pieces, prob.x);
  out.num_pieces = static_cast<int>(pieces.size());
  return out;
}

}  // namespace minenav::mapper
