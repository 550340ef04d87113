#include "pose_estimator/feature/feature_prediction.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/angle.h"
#include "common/config.h"

namespace minenav {
namespace {

constexpr double kAngleEps = 1e-12;

// An angular interval [a0, a1] (a0 < a1, both in [-pi, pi]) covered by one segment.
struct Piece {
  int segment;
  double a0, a1;
};

// A maximal angular interval over which one segment (or nothing, -1) is nearest.
struct Run {
  int segment;
  double a0, a1;  // a1 may exceed pi after the wrap-around merge
  Eigen::Vector2d p0 = Eigen::Vector2d::Zero(), p1 = Eigen::Vector2d::Zero();  // piece ends
  int v0 = -1, v1 = -1;  // map vertex at a piece end, if the end is a segment endpoint
};

Eigen::Vector2d Dir(double a) { return {std::cos(a), std::sin(a)}; }

// Where the ray from p at bearing a meets the infinite line of s.
Eigen::Vector2d OnLine(const Eigen::Vector2d& p, double a, const Segment& s) {
  const Eigen::Vector2d d = Dir(a);
  const Eigen::Vector2d u = s.direction();
  const Eigen::Vector2d n(-u.y(), u.x());
  const double den = n.dot(d);
  if (std::abs(den) < 1e-15) return s.a;
  return p + d * (n.dot(s.a - p) / den);
}

double Bearing(const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
  return std::atan2(q.y() - p.y(), q.x() - p.x());
}

bool SameAngle(double a, double b) { return std::abs(NormalizeAngle(a - b)) < 1e-9; }

}  // namespace

PredictedFeatures PredictFeatures(const FeatureMap& map, const Eigen::Vector2d& p,
                                  const PredictionOptions& options) {
  PredictedFeatures out;
  out.vertex_labels.resize(map.vertices.size());

  // 1. Angular pieces of the segments within range.
  std::vector<Piece> pieces;
  for (int i = 0; i < static_cast<int>(map.segments.size()); ++i) {
    const Segment& s = map.segments[static_cast<size_t>(i)];
    if (PointToSegmentDistance(p, s) > options.max_range) continue;
    double t0 = Bearing(p, s.a);
    double span = NormalizeAngle(Bearing(p, s.b) - t0);
    if (std::abs(span) < kAngleEps || std::abs(std::abs(span) - kPi) < kAngleEps) continue;
    ++out.segments_in_range;
    out.segments_in_range_ids.push_back(i);
    if (span < 0.0) {
      t0 = Bearing(p, s.b);
      span = -span;
    }
    if (t0 + span <= kPi) {
      pieces.push_back({i, t0, t0 + span});
    } else {
      pieces.push_back({i, t0, kPi});
      pieces.push_back({i, -kPi, t0 + span - 2.0 * kPi});
    }
  }

  // 2. Sweep the critical angles; in each interval the nearest active segment is visible.
  std::vector<double> cuts = {-kPi, kPi};
  for (const Piece& pc : pieces) {
    cuts.push_back(pc.a0);
    cuts.push_back(pc.a1);
  }
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end(),
                         [](double a, double b) { return b - a < kAngleEps; }),
             cuts.end());
  std::vector<int> by_start(pieces.size()), by_end(pieces.size());
  for (size_t i = 0; i < pieces.size(); ++i) by_start[i] = by_end[i] = static_cast<int>(i);
  std::sort(by_start.begin(), by_start.end(), [&](int a, int b) {
    return pieces[static_cast<size_t>(a)].a0 < pieces[static_cast<size_t>(b)].a0;
  });
  std::sort(by_end.begin(), by_end.end(), [&](int a, int b) {
    return pieces[static_cast<size_t>(a)].a1 < pieces[static_cast<size_t>(b)].a1;
  });
  std::vector<int> active;
  std::vector<int> slot(pieces.size(), -1);  // index in `active`, -1 if not there
  std::vector<char> removed(pieces.size(), 0);
  size_t next_start = 0, next_end = 0;
  std::vector<Run> runs;
  for (size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double c = cuts[k];
    while (next_start < by_start.size() &&
           pieces[static_cast<size_t>(by_start[next_start])].a0 <= c + kAngleEps) {
      const int id = by_start[next_start++];
      if (removed[static_cast<size_t>(id)]) continue;
      slot[static_cast<size_t>(id)] = static_cast<int>(active.size());
      active.push_back(id);
    }
    while (next_end < by_end.size() &&
           pieces[static_cast<size_t>(by_end[next_end])].a1 <= c + kAngleEps) {
      const int id = by_end[next_end++];
      removed[static_cast<size_t>(id)] = 1;
      const int at = slot[static_cast<size_t>(id)];
      if (at < 0) continue;
      const int last = active.back();
      active[static_cast<size_t>(at)] = last;
      slot[static_cast<size_t>(last)] = at;
      active.pop_back();
      slot[static_cast<size_t>(id)] = -1;
    }
    const double mid = 0.5 * (c + cuts[k + 1]);
    const Eigen::Vector2d d = Dir(mid);
    int best = -1;
    double best_range = options.max_range;
    for (int id : active) {
      const int seg = pieces[static_cast<size_t>(id)].segment;
      const auto hit = RaySegmentIntersection(p, d, map.segments[static_cast<size_t>(seg)]);
      if (hit && *hit < best_range) {
        best_range = *hit;
        best = seg;
      }
    }
    if (!runs.empty() && runs.back().segment == best) {
      runs.back().a1 = cuts[k + 1];
    } else {
      runs.push_back({best, c, cuts[k + 1]});
    }
  }
  if (runs.size() > 1 && runs.front().segment == runs.back().segment) {
    runs.back().a1 = runs.front().a1 + 2.0 * kPi;
    runs.erase(runs.begin());
  }

  for (const Run& r : runs) {
    if (r.segment >= 0) out.visible_segments.push_back(r.segment);
  }
  std::sort(out.visible_segments.begin(), out.visible_segments.end());
  out.visible_segments.erase(std::unique(out.visible_segments.begin(), out.visible_segments.end()),
                             out.visible_segments.end());

  // 3. Piece ends of the visible runs, and whether they are segment endpoints.
  for (Run& r : runs) {
    if (r.segment < 0) continue;
    const Segment& s = map.segments[static_cast<size_t>(r.segment)];
    const auto& sv = map.segment_vertices[static_cast<size_t>(r.segment)];
    r.p0 = OnLine(p, r.a0, s);
    r.p1 = OnLine(p, r.a1, s);
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector2d& e = k == 0 ? s.a : s.b;
      const int v = sv[static_cast<size_t>(k)];
      if (SameAngle(Bearing(p, e), r.a0)) { r.p0 = e; r.v0 = v; }
      if (SameAngle(Bearing(p, e), r.a1)) { r.p1 = e; r.v1 = v; }
    }
  }

  // 4. Corners at the boundaries between runs; collinear neighbours merge into one line.
  const size_t n = runs.size();
  std::vector<char> merge_with_next(n, 0);
  auto other_end = [&](const Run& r, int v) {
    const Segment& s = map.segments[static_cast<size_t>(r.segment)];
    const auto& sv = map.segment_vertices[static_cast<size_t>(r.segment)];
    return sv[0] == v ? s.b : s.a;
  };
  auto range_at = [&](const Run& r, double a) {
    if (r.segment < 0) return std::numeric_limits<double>::infinity();
    return (OnLine(p, a, map.segments[static_cast<size_t>(r.segment)]) - p).norm();
  };
  auto add_corner = [&](int v, const Eigen::Vector2d& arm1, const Eigen::Vector2d& arm2,
                        bool occlusion) {
    const Eigen::Vector2d& vp = map.vertices[static_cast<size_t>(v)];
    if ((vp - p).norm() > options.max_range) return;
    Feature f = MakeCorner(vp, arm1, arm2, occlusion);
    f.map_vertex = v;
    out.features.push_back(f);
    out.vertex_labels[static_cast<size_t>(v)].visible = true;
    out.vertex_labels[static_cast<size_t>(v)].occluding = occlusion;
  };
  for (size_t k = 0; n > 1 && k < n; ++k) {
    const Run& a = runs[k];
    const Run& b = runs[(k + 1) % n];
    if (a.segment >= 0 && b.segment >= 0 && a.v1 >= 0 && a.v1 == b.v0) {
      const Eigen::Vector2d& vp = map.vertices[static_cast<size_t>(a.v1)];
      const Eigen::Vector2d arm1 = (other_end(a, a.v1) - vp).normalized();
      const Eigen::Vector2d arm2 = (other_end(b, b.v0) - vp).normalized();
      if (std::acos(std::clamp(arm1.dot(arm2), -1.0, 1.0)) > kPi - options.collinear_angle) {
        merge_with_next[k] = 1;
        out.vertex_labels[static_cast<size_t>(a.v1)].visible = true;
      } else {
        add_corner(a.v1, arm1, arm2, false);
      }
      continue;
    }
    const double c = a.a1;
    if (a.segment >= 0 && a.v1 >= 0 && range_at(b, c) > range_at(a, c)) {
      const Eigen::Vector2d& vp = map.vertices[static_cast<size_t>(a.v1)];
      add_corner(a.v1, (other_end(a, a.v1) - vp).normalized(), (vp - p).normalized(), true);
    } else if (b.segment >= 0 && b.v0 >= 0 && range_at(a, c) > range_at(b, c)) {
      const Eigen::Vector2d& vp = map.vertices[static_cast<size_t>(b.v0)];
      add_corner(b.v0, (other_end(b, b.v0) - vp).normalized(), (vp - p).normalized(), true);
    }
  }
  // Piece ends that are segment endpoints are visible even where they form no corner.
  for (const Run& r : runs) {
    if (r.v0 >= 0) out.vertex_labels[static_cast<size_t>(r.v0)].visible = true;
    if (r.v1 >= 0) out.vertex_labels[static_cast<size_t>(r.v1)].visible = true;
  }

  // 5. Line features: chains of runs joined by collinear merges.
  size_t first = 0;
  if (n > 1) {
    // Start at a run that does not continue the previous one, so no chain is split.
    for (size_t k = 0; k < n; ++k) {
      if (!merge_with_next[(k + n - 1) % n]) {
        first = k;
        break;
      }
    }
  }
  for (size_t i = 0; i < n;) {
    const size_t k0 = (first + i) % n;
    size_t len = 1;
    while (len < n && merge_with_next[(k0 + len - 1) % n]) ++len;
    i += len;
    const Run& r0 = runs[k0];
    const Run& r1 = runs[(k0 + len - 1) % n];
    if (r0.segment < 0) continue;
    Feature f = MakeLine(r0.p0, r1.p1);
    if (f.length < options.min_line_length) continue;
    if (len == 1) {
      // The exact line of the segment, not of the (possibly clipped) chord.
      const Segment& s = map.segments[static_cast<size_t>(r0.segment)];
      const Feature exact = MakeLine(s.a, s.b);
      f.distance = exact.distance;
      f.orientation = exact.orientation;
    }
    f.map_segment = r0.segment;
    out.features.push_back(f);
  }

  // 6. Order by azimuth around the position.
  auto azimuth = [&](const Feature& f) {
    const Eigen::Vector2d q = f.type == FeatureType::kCorner ? f.position : 0.5 * (f.start + f.end);
    return Bearing(p, q);
  };
  std::stable_sort(out.features.begin(), out.features.end(),
                   [&](const Feature& a, const Feature& b) { return azimuth(a) < azimuth(b); });
  return out;
}

void DeclareOptions(OptionScope scope, PredictionOptions& o) {
  scope.AddDouble("max_range", &o.max_range, "m",
                  "the scanner's useful range: farther map parts are not predicted (50 m, the Cyclone's; each "
                  "scan's own max_range caps it)",
                  0.1, 1000.0);
  scope.AddDouble("min_line_length", &o.min_line_length, "m",
                  "shorter visible pieces of map segments are not predicted as lines: too few points would fall "
                  "on them to fit (0.3 m)",
                  0.0, 100.0);
  scope.AddDouble("collinear_angle", &o.collinear_angle, "rad",
                  "visible neighbours bending less than this are one line and no corner: maps often split a "
                  "straight wall into several segments (0.035 rad, 2 deg)",
                  0.0, 1.0);
}

}  // namespace minenav
