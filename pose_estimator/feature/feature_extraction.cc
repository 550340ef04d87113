#include "pose_estimator/feature/feature_extraction.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "common/config.h"
#include "common/scan_split.h"
#include "pose_estimator/feature/incremental_line_fitter.h"

namespace minenav {
namespace {

struct Piece {
  std::vector<ScanPoint> points;
  bool closed = false;           // a full-circle scan without a single break
  bool occluding_start = false;  // the start hides something farther (or open space)
  bool occluding_end = false;
};

// A robust line fit over a span of points, leaving out points near the corners that
// bound it.
struct SpanLine {
  LineFit fit;
  int inliers = 0;
  ScanPoint first, last;  // first and last inlier in scan order
};

// `fit_out` receives the last fit even when the span is rejected (for splitting).
std::optional<SpanLine> FitSpan(const std::vector<ScanPoint>& span,
                                const std::vector<Eigen::Vector2d>& exclude,
                                const ExtractionOptions& o, LineFit* fit_out) {
  std::vector<size_t> idx;
  for (size_t i = 0; i < span.size(); ++i) {
    bool near = false;
    for (const Eigen::Vector2d& e : exclude) near = near || (span[i].point - e).norm() < o.corner_gap;
    if (!near) idx.push_back(i);
  }
  if (static_cast<int>(idx.size()) < o.min_line_points) return std::nullopt;
  const size_t total = idx.size();
  SpanLine s;
  // Start from the line through two points of the span that has the most points within
  // 2 sigma (deterministic pairs a third of the span apart), so a column jutting from
  // the wall or clutter against it cannot tilt the first fit; then refine by refitting
  // to the points within outlier_factor sigma.
  std::vector<size_t> keep;
  {
    const size_t m = idx.size();
    const size_t gap = std::max<size_t>(1, m / 3);
    const size_t tries = std::min<size_t>(24, m - gap);
    size_t best = 0;
    for (size_t t = 0; t < tries; ++t) {
      const size_t j = t * (m - gap) / tries;
      const Eigen::Vector2d a = span[idx[j]].point, b = span[idx[j + gap]].point;
      if ((b - a).norm() < 1e-9) continue;
      const Eigen::Vector2d d = (b - a).normalized();
      const Eigen::Vector2d n(-d.y(), d.x());
      std::vector<size_t> in;
      for (size_t i : idx) {
        if (std::abs(n.dot(span[i].point - a)) <= 2.0 * o.noise_sigma) in.push_back(i);
      }
      if (in.size() > best) {
        best = in.size();
        keep = std::move(in);
      }
    }
    if (static_cast<int>(keep.size()) < o.min_line_points) keep = idx;
  }
  for (int iter = 0; iter < 6; ++iter) {
    IncrementalLineFitter fitter(span[keep.front()].point, o.noise_sigma);
    for (size_t i : keep) fitter.Add(span[i].point);
    s.fit = fitter.Fit();
    *fit_out = s.fit;
    if (!s.fit.valid) return std::nullopt;
    const Eigen::Vector2d n(-s.fit.direction.y(), s.fit.direction.x());
    std::vector<size_t> next;
    for (size_t i : idx) {
      if (std::abs(n.dot(span[i].point - s.fit.centroid)) <= o.outlier_factor * o.noise_sigma) {
        next.push_back(i);
      }
    }
    if (static_cast<int>(next.size()) < o.min_line_points) return std::nullopt;
    if (next == keep) break;
    keep = std::move(next);
  }
  s.inliers = static_cast<int>(keep.size());
  s.first = span[keep.front()];
  s.last = span[keep.back()];
  if (s.fit.rms > o.max_line_rms) return std::nullopt;
  if (static_cast<double>(s.inliers) < o.min_inlier_fraction * static_cast<double>(total)) {
    return std::nullopt;
  }
  return s;
}

// Lines of a span in scan order. A run of consecutive points off the line inside the span
// (a column jutting from the wall, clutter against it) splits it, and each side is fit on
// its own, so the run neither tilts the line nor hides the wall on either side.
std::vector<SpanLine> FitSpanLines(const std::vector<ScanPoint>& span,
                                   const std::vector<Eigen::Vector2d>& exclude,
                                   const ExtractionOptions& o, int depth = 0) {
  LineFit fit;
  const std::optional<SpanLine> line = FitSpan(span, exclude, o, &fit);
  if (depth < 4 && fit.valid) {
    const Eigen::Vector2d n(-fit.direction.y(), fit.direction.x());
    const double limit = o.outlier_factor * o.noise_sigma;
    int best_start = -1, best_len = 0, start = -1, len = 0;
    for (int i = 0; i < static_cast<int>(span.size()); ++i) {
      if (std::abs(n.dot(span[static_cast<size_t>(i)].point - fit.centroid)) > limit) {
        if (len == 0) start = i;
        ++len;
        if (len > best_len) {
          best_len = len;
          best_start = start;
        }
      } else {
        len = 0;
      }
    }
    const int after = best_start + best_len;
    if (best_len >= o.split_run_points && best_start >= o.min_line_points &&
        static_cast<int>(span.size()) - after >= o.min_line_points) {
      const std::vector<ScanPoint> left(span.begin(), span.begin() + best_start);
      const std::vector<ScanPoint> right(span.begin() + after, span.end());
      std::vector<SpanLine> out = FitSpanLines(left, exclude, o, depth + 1);
      std::vector<SpanLine> more = FitSpanLines(right, exclude, o, depth + 1);
      out.insert(out.end(), more.begin(), more.end());
      return out;
    }
  }
  if (line) return {*line};
  return {};
}

Eigen::Vector2d Project(const LineFit& f, const Eigen::Vector2d& p) {
  return f.centroid + f.direction * f.direction.dot(p - f.centroid);
}

// Where the ray from the origin at `bearing` meets the fitted line.
Eigen::Vector2d RayOnLine(const LineFit& f, double bearing) {
  const Eigen::Vector2d d(std::cos(bearing), std::sin(bearing));
  const Eigen::Vector2d n(-f.direction.y(), f.direction.x());
  const double den = n.dot(d);
  if (std::abs(den) < 1e-6) return Project(f, f.centroid);
  return d * (n.dot(f.centroid) / den);
}

bool IntersectFits(const LineFit& a, const LineFit& b, Eigen::Vector2d* out) {
  const Eigen::Vector2d d1 = a.direction, d2 = b.direction;
  const double den = d1.x() * d2.y() - d1.y() * d2.x();
  if (std::abs(den) < std::sin(DegToRad(20.0))) return false;
  const Eigen::Vector2d w = b.centroid - a.centroid;
  *out = a.centroid + d1 * ((w.x() * d2.y() - w.y() * d2.x()) / den);
  return true;
}

Eigen::Vector2d AwayFrom(const LineFit& f, const Eigen::Vector2d& v) {
  return f.direction.dot(f.centroid - v) >= 0 ? f.direction : Eigen::Vector2d(-f.direction);
}

// The scan's pieces (common/scan_split.h): readings are neighbours if no more than one
// reading is missing between them (a lone dropout does not cut a wall) and they are close
// in space. On a full circle the piece that straddles index 0 stays whole, listed last:
// pieces are listed where they start.
std::vector<Piece> SplitIntoPieces(const LadarScan& scan, const std::vector<ScanPoint>& pts,
                                   const ExtractionOptions& o) {
  const size_t total = scan.ranges.size();
  std::vector<Eigen::Vector2d> points(total, Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN()));
  std::vector<double> ranges(total, 0.0);
  std::vector<const ScanPoint*> point_of_reading(total, nullptr);
  for (const ScanPoint& p : pts) {
    const auto i = static_cast<size_t>(p.index);
    points[i] = p.point;
    ranges[i] = p.range;
    point_of_reading[i] = &p;
  }
  ScanSplitOptions split;
  split.break_distance = o.break_distance;
  split.break_range_factor = o.break_range_factor;
  split.min_points = o.min_piece_points;
  split.max_missing_readings = 1;
  split.wrap_around = WrapAround::kFullTurn;
  split.seam_partial_scan_first = false;
  std::vector<Piece> pieces;
  const ScanReadings readings{.points = points, .ranges = ranges, .angle_step = scan.angle_step};
  for (const PartialScanReadings& partial : SplitScan(readings, split)) {
    Piece& piece = pieces.emplace_back();
    piece.closed = partial.closed;
    piece.points.reserve(partial.readings.size());
    for (const int i : partial.readings) piece.points.push_back(*point_of_reading[static_cast<size_t>(i)]);
  }
  return pieces;
}

std::vector<Piece> BreakScan(const LadarScan& scan, const std::vector<ScanPoint>& pts,
                             const ExtractionOptions& o) {
  std::vector<Piece> pieces = SplitIntoPieces(scan, pts, o);
  const int total = static_cast<int>(scan.ranges.size());
  const bool full_circle = CoversFullTurn(scan.ranges.size(), scan.angle_step);

  // An end occludes if the reading just beyond it is missing (nothing within range) or
  // farther away; a scan edge of a partial scan occludes nothing we can know of.
  auto neighbour_range = [&](int index, int dir) -> std::optional<double> {
    int j = index + dir;
    if (full_circle) {
      j = (j + total) % total;
    } else if (j < 0 || j >= total) {
      return std::nullopt;
    }
    const auto r = static_cast<double>(scan.ranges[static_cast<size_t>(j)]);
    return scan.IsValid(static_cast<size_t>(j)) ? r : std::numeric_limits<double>::infinity();
  };
  for (Piece& pc : pieces) {
    const ScanPoint& a = pc.points.front();
    const ScanPoint& b = pc.points.back();
    const auto ra = neighbour_range(a.index, -1);
    const auto rb = neighbour_range(b.index, +1);
    if (pc.closed) continue;
    pc.occluding_start = ra && *ra > a.range + o.break_distance;
    pc.occluding_end = rb && *rb > b.range + o.break_distance;
  }
  return pieces;
}

}  // namespace

ExtractedFeatures ExtractFeatures(const LadarScan& scan, const ExtractionOptions& o) {
  ExtractedFeatures out;
  const std::vector<ScanPoint> pts = ScanPointsInSensorFrame(scan);
  out.num_points = static_cast<int>(pts.size());
  const std::vector<Piece> pieces = BreakScan(scan, pts, o);
  out.num_pieces = static_cast<int>(pieces.size());
  const double half_step = 0.5 * scan.angle_step;

  for (const Piece& pc : pieces) {
    const int m = static_cast<int>(pc.points.size());
    // A closed loop is padded with its own ends so the operator sees across the seam.
    int pad = 0;
    if (pc.closed) {
      while (pad + 1 < m &&
             (pc.points[static_cast<size_t>(pad)].point - pc.points[0].point).norm() < 1.5 * o.corner.arm_length) {
        ++pad;
      }
      pad += 2;
      pad = std::min(pad, m - 1);
    }
    std::vector<Eigen::Vector2d> xy;
    for (int i = -pad; i < m + pad; ++i) {
      xy.push_back(pc.points[static_cast<size_t>((i % m + m) % m)].point);
    }
    std::vector<CornerCandidate> corners;
    for (CornerCandidate c : ApplyCornerOperator(xy, o.corner)) {
      c.index -= pad;
      if (c.index < 0 || c.index >= m) continue;
      if (!corners.empty() && corners.back().index == c.index) continue;
      corners.push_back(c);
    }
    const int nc = static_cast<int>(corners.size());

    // Spans of points between breakpoints (piece ends, corners). Open piece: nc + 1 spans,
    // corner k between spans k and k + 1. Closed loop: nc spans (one if no corner), span k
    // from corner k to corner k + 1, corner k between spans k - 1 and k.
    struct Span {
      std::vector<ScanPoint> points;
      int corner_before = -1, corner_after = -1;
    };
    std::vector<Span> spans;
    auto take = [&](int from, int to) {  // inclusive, cyclic for closed loops
      std::vector<ScanPoint> v;
      for (int i = from;; i = (i + 1) % m) {
        v.push_back(pc.points[static_cast<size_t>(i)]);
        if (i == to) break;
      }
      return v;
    };
    if (!pc.closed) {
      for (int k = 0; k <= nc; ++k) {
        const int i0 = k == 0 ? 0 : corners[static_cast<size_t>(k - 1)].index;
        const int i1 = k == nc ? m - 1 : corners[static_cast<size_t>(k)].index;
        spans.push_back({take(i0, i1), k - 1, k < nc ? k : -1});
      }
    } else if (nc == 0) {
      spans.push_back({pc.points, -1, -1});
    } else {
      for (int k = 0; k < nc; ++k) {
        spans.push_back({take(corners[static_cast<size_t>(k)].index,
                              corners[static_cast<size_t>((k + 1) % nc)].index),
                         k, (k + 1) % nc});
      }
    }
    std::vector<std::vector<SpanLine>> lines(spans.size());
    for (size_t k = 0; k < spans.size(); ++k) {
      std::vector<Eigen::Vector2d> exclude;
      if (spans[k].corner_before >= 0) exclude.push_back(corners[static_cast<size_t>(spans[k].corner_before)].vertex);
      if (spans[k].corner_after >= 0) exclude.push_back(corners[static_cast<size_t>(spans[k].corner_after)].vertex);
      lines[k] = FitSpanLines(spans[k].points, exclude, o);
    }
    auto span_before = [&](int k) { return pc.closed ? (k + nc - 1) % nc : k; };
    auto span_after = [&](int k) { return pc.closed ? k : k + 1; };

    // Corners: at the intersection of the neighbouring lines when both exist.
    std::vector<Eigen::Vector2d> vertex(static_cast<size_t>(nc));
    for (int k = 0; k < nc; ++k) {
      const CornerCandidate& c = corners[static_cast<size_t>(k)];
      Eigen::Vector2d v = c.vertex, arm_before = c.arm_before, arm_after = c.arm_after;
      int points = c.num_points;
      double rms = c.fit_rms;
      const auto& lbs = lines[static_cast<size_t>(span_before(k))];
      const auto& las = lines[static_cast<size_t>(span_after(k))];
      const SpanLine* lb = lbs.empty() ? nullptr : &lbs.back();
      const SpanLine* la = las.empty() ? nullptr : &las.front();
      Eigen::Vector2d w;
      if (lb && la && IntersectFits(lb->fit, la->fit, &w) && (w - c.vertex).norm() < o.corner.arm_length) {
        v = w;
        arm_before = AwayFrom(lb->fit, v);
        arm_after = AwayFrom(la->fit, v);
        points = lb->inliers + la->inliers;
        rms = std::max(lb->fit.rms, la->fit.rms);
      }
      vertex[static_cast<size_t>(k)] = v;
      Feature f = MakeCorner(v, arm_before, arm_after, false);
      f.num_points = points;
      f.fit_rms = rms;
      out.features.push_back(f);
    }

    // Lines, from the corner (or the projected first / last inlier) to the next.
    for (size_t k = 0; k < spans.size(); ++k) {
      const size_t nl = lines[k].size();
      for (size_t j = 0; j < nl; ++j) {
        const SpanLine& s = lines[k][j];
        const int cb = j == 0 ? spans[k].corner_before : -1;
        const int ca = j + 1 == nl ? spans[k].corner_after : -1;
        const Eigen::Vector2d a = cb >= 0 ? Project(s.fit, vertex[static_cast<size_t>(cb)]) : Project(s.fit, s.first.point);
        const Eigen::Vector2d b = ca >= 0 ? Project(s.fit, vertex[static_cast<size_t>(ca)]) : Project(s.fit, s.last.point);
        if ((b - a).norm() < o.min_line_length) continue;
        const bool ccw = a.x() * b.y() - a.y() * b.x() >= 0.0;  // as seen from the sensor
        Feature f = MakeLine(ccw ? a : b, ccw ? b : a);
        f.num_points = s.inliers;
        f.fit_rms = s.fit.rms;
        out.features.push_back(f);

        // Occlusion corners at occluding piece ends covered by this line. The surface ends
        // somewhere between the last ray that saw it and the next: take the middle.
        if (!o.occlusion_corners || pc.closed) continue;
        for (int side = 0; side < 2; ++side) {
          const bool occluding = side == 0 ? (k == 0 && j == 0 && pc.occluding_start)
                                           : (k + 1 == spans.size() && j + 1 == nl && pc.occluding_end);
          if (!occluding) continue;
          const ScanPoint& last = side == 0 ? s.first : s.last;
          const double outward = side == 0 ? -half_step : half_step;
          const Eigen::Vector2d v = RayOnLine(s.fit, last.bearing + outward);
          const Eigen::Vector2d seen = RayOnLine(s.fit, last.bearing);
          const Eigen::Vector2d inward = ((side == 0 ? b : a) - v).normalized();
          Feature c = MakeCorner(v, inward, v.normalized(), true);
          c.num_points = s.inliers;
          c.fit_rms = s.fit.rms;
          const double span_len = 2.0 * (v - seen).norm();
          c.position_variance = span_len * span_len / 12.0;
          out.features.push_back(c);
        }
      }
    }
  }
  SortByAzimuth(&out.features);
  return out;
}

void DeclareOptions(OptionScope scope, ExtractionOptions& o) {
  scope.AddDouble("break_distance", &o.break_distance, "m",
                  "a gap between successive points larger than this (plus break_range_factor of the range) breaks "
                  "the scan into pieces at occlusions (0.3 m)",
                  0.01, 100.0);
  scope.AddDouble("break_range_factor", &o.break_range_factor, "1",
                  "plus this fraction of the range: points on a wall seen at a grazing angle lie farther apart far "
                  "away (0.05)",
                  0.0, 10.0);
  scope.AddInt("min_piece_points", &o.min_piece_points, "pieces with fewer points are thrown out as clutter (6)", 1,
               100000);
  DeclareOptions(scope.Nested("corner"), o.corner);
  scope.AddDouble("noise_sigma", &o.noise_sigma, "m",
                  "range noise of the sensor, for the line fits: the most they assume when the scan's own is "
                  "measured (measure_range_noise), else what they use (0.1 m: the Cyclone's; the Typhoon's is 0.044)",
                  0.001, 1.0);
  scope.AddDouble("outlier_factor", &o.outlier_factor, "1",
                  "line fits drop points farther than this many noise_sigma and refit, so clutter against a wall "
                  "does not bend the line (3)",
                  0.5, 100.0);
  scope.AddDouble("corner_gap", &o.corner_gap, "m",
                  "points this close to a corner stay out of the line fits: the corner's rounding would bend the "
                  "line (0.15 m)",
                  0.0, 10.0);
  scope.AddInt("min_line_points", &o.min_line_points, "points a line needs after dropping outliers (8)", 2, 100000);
  scope.AddInt("split_run_points", &o.split_run_points,
               "a run of this many consecutive points off a line splits it in two (a small column jutting out) (3)",
               1, 100000);
  scope.AddDouble("min_line_length", &o.min_line_length, "m",
                  "shorter lines are not features: their direction is too uncertain (0.5 m)", 0.0, 100.0);
  scope.AddDouble("max_line_rms", &o.max_line_rms, "m",
                  "largest RMS of a line fit after dropping outliers, ~1.3 noise_sigma: a curved rib or rubble "
                  "gives no line (0.13 m)",
                  0.001, 10.0);
  scope.AddDouble("min_inlier_fraction", &o.min_inlier_fraction, "1",
                  "fraction of a span's points that must lie on its line (0.7)", 0.0, 1.0);
  scope.AddBool("occlusion_corners", &o.occlusion_corners,
                "report the visible end of a piece that hides something farther (or open space) as an occlusion "
                "corner (arms: the line and the ray)");
}

}  // namespace minenav
