#include "mapper/map_appearance.h"

#include <cmath>

#include "mapper/map_expansion.h"

namespace minenav::mapper {

namespace {

using Vec = Eigen::Vector2d;
using Kind = RunAnchor::Kind;

// m; a cut this close to an existing vertex uses that vertex (no zero-length segments).
constexpr double kVertexSnap = 1e-3;

Vec Foot(const Contour& c, const PointMatch& m) {
  const Segment s = c.GetSegment(m.segment.segment);
  const Vec d = s.b - s.a;
  const double h = d.norm();
  return h > 0.0 ? Vec(s.a + (m.along / h) * d) : s.a;
}

// Arc length from the contour's first vertex to `p` on segment k.
double ArcPosition(const Contour& c, int k, const Vec& p) {
  double arc = 0.0;
  for (int j = 0; j < k; ++j) arc += c.GetSegment(j).length();
  return arc + (p - c.points[static_cast<size_t>(c.SegmentStart(k))]).norm();
}

// The segment containing p, preferring contour `prefer`; contour -1 when none.
SegmentRef SegmentContaining(const ContourMap& map, const Vec& p, int prefer) {
  SegmentRef best;
  double best_d = kVertexSnap;
  for (const SegmentRef& r : map.SegmentsNear(p, kVertexSnap)) {
    const double d = PointToSegmentDistance(p, map.Get(r.contour).GetSegment(r.segment)) -
                     (r.contour == prefer ? kVertexSnap : 0.0);
    if (d < best_d) {
      best_d = d;
      best = r;
    }
  }
  return best;
}

// Opens the contour through p there (Cut, then Detach): afterwards an open contour ends at
// p and, unless p was an open end, one starts at p. Records the contours it touched.
void OpenAt(ContourMap& map, const Vec& p, int prefer, std::vector<int>* touched) {
  const SegmentRef r = SegmentContaining(map, p, prefer);
  if (r.contour < 0) return;
  const Contour& c = map.Get(r.contour);
  const int s = c.SegmentStart(r.segment), e = c.SegmentEnd(r.segment);
  int v;
  if ((c.points[static_cast<size_t>(s)] - p).norm() < kVertexSnap)
    v = s;
  else if ((c.points[static_cast<size_t>(e)] - p).norm() < kVertexSnap)
    v = e;
  else
    v = map.Cut(r.contour, r.segment, p);
  const std::optional<int> tail = map.Detach(r.contour, v);
  touched->push_back(r.contour);
  if (tail && *tail != r.contour) touched->push_back(*tail);
}

// An open contour whose last (want_end) or first vertex lies at p; -1 if none. Opened
// contours keep exact copies of the cut vertex, so a tight tolerance is enough.
int OpenContourAt(const ContourMap& map, const Vec& p, bool want_end) {
  for (const SegmentRef& r : map.SegmentsNear(p, kVertexSnap)) {
    const Contour& c = map.Get(r.contour);
    if (c.closed) continue;
    const Vec& v = want_end ? c.points.back() : c.points.front();
    if ((v - p).norm() < 1e-9) return c.id;
  }
  return -1;
}

RunAnchor Anchor(const ContourMap& map, const PointMatch& m, const Vec& p, bool left, double snap) {
  RunAnchor a;
  if (!m.matched()) return a;
  const Contour& c = map.Get(m.segment.contour);
  a.contour = c.id;
  a.segment = m.segment.segment;
  if (!c.closed) {
    // Before the run the contour must end here; after it, start here.
    const bool on_end_segment = left ? a.segment == c.NumSegments() - 1 : a.segment == 0;
    const Vec& v = left ? c.points.back() : c.points.front();
    if (on_end_segment || (v - p).norm() <= snap) {
      a.kind = left ? Kind::kContourEnd : Kind::kContourStart;
      a.point = v;
      return a;
    }
  }
  a.kind = Kind::kInterior;
  a.point = Foot(c, m);
  return a;
}

}  // namespace

RunAnchor LeftAnchor(const ContourMap& map, const PointMatch& match, const Vec& point, double snap) {
  return Anchor(map, match, point, true, snap);
}

RunAnchor RightAnchor(const ContourMap& map, const PointMatch& match, const Vec& point, double snap) {
  return Anchor(map, match, point, false, snap);
}

int AppearanceCase(const RunAnchor& left, const RunAnchor& right) {
  const bool l_end = left.kind == Kind::kContourEnd, l_in = left.kind == Kind::kInterior;
  const bool r_start = right.kind == Kind::kContourStart, r_in = right.kind == Kind::kInterior;
  if (l_end) return r_start ? 3 : r_in ? 5 : 7;
  if (l_in) return r_start ? 6 : r_in ? 4 : 8;
  return r_start ? 1 : r_in ? 2 : 0;
}

AppearanceEdit ApplyAppearance(ContourMap& map, const std::vector<Vec>& run, RunAnchor left, RunAnchor right,
                               const MapExpansionOptions& o) {
  AppearanceEdit out;
  if (run.empty()) return out;
  const double run_length = PolylineLength(run, false);
  auto drop_interior = [](RunAnchor& a) {
    if (a.kind == Kind::kInterior) a = RunAnchor{};
  };
  // A left anchor that is not an end (a start vertex, say) and a right one that is not a
  // start can only be interior; the static walk treats both as nothing.
  if (!o.splice_interior || run_length < o.min_splice_length) {
    drop_interior(left);
    drop_interior(right);
  }
  if (left.kind == Kind::kInterior && right.kind == Kind::kInterior && left.contour == right.contour) {
    const Contour& c = map.Get(left.contour);
    double bypass = ArcPosition(c, right.segment, right.point) - ArcPosition(c, left.segment, left.point);
    if (c.closed && bypass < 0.0) bypass += c.Length();
    const double span = run_length + (run.front() - left.point).norm() + (run.back() - right.point).norm();
    if (bypass < 0.0 || bypass > o.max_bypass_ratio * span) {
      drop_interior(left);
      drop_interior(right);
    }
  }
  out.case_number = AppearanceCase(left, right);

  // Splice: open the contours at the interior anchors; the runs attach to the cut ends.
  if (left.kind == Kind::kInterior) OpenAt(map, left.point, left.contour, &out.spliced);
  if (right.kind == Kind::kInterior) OpenAt(map, right.point, right.contour, &out.spliced);
  int first = left.kind == Kind::kNone ? -1 : OpenContourAt(map, left.point, true);
  const int second = right.kind == Kind::kNone ? -1 : OpenContourAt(map, right.point, false);

  const double len = o.nominal_segment_length;
  if (first >= 0 && second >= 0) {
    std::vector<Vec> path = run;
    path.insert(path.begin(), left.point);
    path.push_back(right.point);
    const std::vector<Vec> v = PickVertices(path, len);
    const std::vector<Vec> bridge(v.begin() + 1, v.end() - 1);
    if (first != second || map.Get(first).NumPoints() + static_cast<int>(bridge.size()) >= 3) {
      out.contour = map.Join(first, second, bridge);
      out.connected = true;
      return out;
    }
  }
  if (first >= 0) {
    std::vector<Vec> path = run;
    path.insert(path.begin(), left.point);
    const std::vector<Vec> v = PickVertices(path, len);
    map.ExtendEnd(first, std::vector<Vec>(v.begin() + 1, v.end()));
    out.contour = first;
    out.extended = true;
  } else if (second >= 0) {
    std::vector<Vec> path = run;
    path.push_back(right.point);
    const std::vector<Vec> v = PickVertices(path, len);
    map.ExtendStart(second, std::vector<Vec>(v.begin(), v.end() - 1));
    out.contour = second;
    out.extended = true;
  } else {
    out.contour = map.Create(PickVertices(run, len));
  }
  return out;
}

}  // namespace minenav::mapper
