#include "pose_estimator/segment_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace minenav {

GridFrame GridFrame::Covering(const std::vector<Segment>& segments, double cell_size, double margin) {
  double lo_x = std::numeric_limits<double>::infinity(), lo_y = lo_x;
  double hi_x = -lo_x, hi_y = -lo_x;
  for (const Segment& s : segments) {
    lo_x = std::min({lo_x, s.a.x(), s.b.x()});
    lo_y = std::min({lo_y, s.a.y(), s.b.y()});
    hi_x = std::max({hi_x, s.a.x(), s.b.x()});
    hi_y = std::max({hi_y, s.a.y(), s.b.y()});
  }
  GridFrame f;
  f.cell = cell_size;
  if (segments.empty()) {
    f.nx = f.ny = 1;
    return f;
  }
  f.x0 = lo_x - margin - cell_size;
  f.y0 = lo_y - margin - cell_size;
  f.nx = static_cast<int>(std::ceil((hi_x + margin + cell_size - f.x0) / cell_size)) + 1;
  f.ny = static_cast<int>(std::ceil((hi_y + margin + cell_size - f.y0) / cell_size)) + 1;
  return f;
}

int GridFrame::CellX(double x) const {
  const double c = std::floor((x - x0) / cell);
  // Clamp before converting so far-away or NaN points cannot overflow an int.
  if (!(c >= -1.0)) return -1;
  if (c > nx) return nx;
  return static_cast<int>(c);
}

int GridFrame::CellY(double y) const {
  const double c = std::floor((y - y0) / cell);
  if (!(c >= -1.0)) return -1;
  if (c > ny) return ny;
  return static_cast<int>(c);
}

namespace {
double PointBoxDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  const double dx = std::max({lo.x() - p.x(), 0.0, p.x() - hi.x()});
  const double dy = std::max({lo.y() - p.y(), 0.0, p.y() - hi.y()});
  return std::hypot(dx, dy);
}
bool Inside(const Eigen::Vector2d& p, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  return p.x() >= lo.x() && p.x() <= hi.x() && p.y() >= lo.y() && p.y() <= hi.y();
}
}  // namespace

double BoxSegmentMinDistance(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const Segment& s) {
  if (Inside(s.a, lo, hi) || Inside(s.b, lo, hi)) return 0.0;
  const Eigen::Vector2d c[4] = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
  for (int k = 0; k < 4; ++k) {
    if (SegmentIntersection(s, Segment(c[k], c[(k + 1) % 4]))) return 0.0;
  }
  // Disjoint convex sets: the least distance is between a vertex of one and the other.
  double best = std::min(PointBoxDistance(s.a, lo, hi), PointBoxDistance(s.b, lo, hi));
  for (const Eigen::Vector2d& corner : c) best = std::min(best, PointToSegmentDistance(corner, s));
  return best;
}

double BoxSegmentMaxDistance(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const Segment& s) {
  const Eigen::Vector2d c[4] = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
  double worst = 0.0;
  for (const Eigen::Vector2d& corner : c) worst = std::max(worst, PointToSegmentDistance(corner, s));
  return worst;
}

std::vector<std::pair<int, int>> CellsTouchedBySegment(const GridFrame& frame, const Segment& s) {
  std::vector<std::pair<int, int>> out;
  const int x_lo = std::max(0, frame.CellX(std::min(s.a.x(), s.b.x())));
  const int x_hi = std::min(frame.nx - 1, frame.CellX(std::max(s.a.x(), s.b.x())));
  const int y_lo = std::max(0, frame.CellY(std::min(s.a.y(), s.b.y())));
  const int y_hi = std::min(frame.ny - 1, frame.CellY(std::max(s.a.y(), s.b.y())));
  const Eigen::Vector2d d = s.b - s.a;
  const double len = d.norm();
  for (int iy = y_lo; iy <= y_hi; ++iy) {
    for (int ix = x_lo; ix <= x_hi; ++ix) {
      const Eigen::Vector2d lo = frame.CellMin(ix, iy);
      const Eigen::Vector2d hi = lo + Eigen::Vector2d(frame.cell, frame.cell);
      // Cheap reject: the line through s must pass within half a diagonal of the centre.
      if (len > 0.0) {
        const Eigen::Vector2d centre = 0.5 * (lo + hi);
        const Eigen::Vector2d w = centre - s.a;
        const double perp = std::abs(d.x() * w.y() - d.y() * w.x()) / len;
        if (perp > frame.cell * 0.7072) continue;
      }
      if (BoxSegmentMinDistance(lo, hi, s) <= 0.0) out.emplace_back(ix, iy);
    }
  }
  return out;
}

}  // namespace minenav
