#include "planner/contour_free_space.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <tuple>

#include "common/angle.h"
#include "common/config.h"
#include "planner/footprint.h"

namespace minenav {
namespace {

constexpr double kTouch = 1e-6;  // m: a crossing this close to a frontier's end point is its joint

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Signed turn (rad, left positive) from direction u onto direction v.
double Turn(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return std::atan2(Cross(u, v), u.dot(v)); }

// The direction of the polyline leaving its first point (forward = true walks from the front,
// else from the back towards the front), skipping repeated points; zero when all coincide.
Eigen::Vector2d EndDirection(const std::vector<Eigen::Vector2d>& p, bool at_start) {
  const size_t n = p.size();
  for (size_t k = 1; k < n; ++k) {
    const Eigen::Vector2d d = at_start ? Eigen::Vector2d(p[k] - p[0]) : Eigen::Vector2d(p[n - 1] - p[n - 1 - k]);
    if (d.norm() > kTouch) return d;
  }
  return Eigen::Vector2d::Zero();
}

// Does segment f cross segment w anywhere but at f's own end points?
bool CrossesAwayFromEnds(const Segment& f, const Segment& w) {
  const std::optional<Eigen::Vector2d> x = SegmentIntersection(f, w);
  if (!x) return false;
  return (*x - f.a).norm() > kTouch && (*x - f.b).norm() > kTouch;
}

struct OpenEnd {
  Eigen::Vector2d end, end_dir;      // the contour's last point, the direction arriving there
  Eigen::Vector2d start, start_dir;  // its first point, the direction leaving it
};

struct Pair {
  double length;
  int end, start;  // indices into the open ends
};

}  // namespace

std::string ValidateOptions(const FreeSpaceOptions& o) {
  if (!(o.min_interior_angle_deg >= 0.0 && o.min_interior_angle_deg < 180.0))
    return "free_space.min_interior_angle_deg must be in [0, 180) deg";
  if (o.probe_rays < 1 || o.probe_rays > 64) return "free_space.probe_rays must be in 1..64";
  if (!(o.probe_range > 0.0) || !std::isfinite(o.probe_range)) return "free_space.probe_range must be > 0 m";
  return "";
}

void DeclareOptions(OptionScope scope, FreeSpaceOptions& o) {
  scope.AddDouble("min_interior_angle_deg", &o.min_interior_angle_deg, "deg",
                  "a frontier leaving less interior angle than this with the contour it joins does not continue it",
                  0.0, 179.0);
  scope.AddInt("probe_rays", &o.probe_rays, "rays that decide whether a point is in the known free space", 1, 64);
  scope.AddDouble("probe_range", &o.probe_range, "m", "how far those rays look (nothing hit: unknown)", 1.0, 1e5);
}

namespace {

// m between a segment and a polygon (0 when they cross or the segment is inside).
double SegmentPolygonDistance(const Segment& s, const std::vector<Eigen::Vector2d>& polygon) {
  if (PolygonContains(polygon, s.a) || PolygonContains(polygon, s.b)) return 0.0;
  double d = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < polygon.size(); ++k) {
    const Segment edge(polygon[k], polygon[(k + 1) % polygon.size()]);
    if (SegmentIntersection(s, edge)) return 0.0;
    d = std::min(
        {d, PointToSegmentDistance(s.a, edge), PointToSegmentDistance(s.b, edge), PointToSegmentDistance(edge.a, s)});
  }
  return d;
}

}  // namespace

std::vector<Segment> FrontiersAwayFrom(const std::vector<Segment>& frontiers,
                                       const std::vector<Eigen::Vector2d>& polygon, double margin, int* dropped) {
  std::vector<Segment> out;
  int n = 0;
  for (const Segment& f : frontiers) {
    if (SegmentPolygonDistance(f, polygon) < margin)
      ++n;
    else
      out.push_back(f);
  }
  if (dropped != nullptr) *dropped = n;
  return out;
}

std::vector<Segment> ContourFreeSpace::Boundary(bool allow_unknown) const {
  std::vector<Segment> out = walls;
  if (!allow_unknown) out.insert(out.end(), frontiers.begin(), frontiers.end());
  return out;
}

ContourFreeSpace MakeContourFreeSpace(const std::vector<mapper::Contour>& contours, const FreeSpaceOptions& options) {
  ContourFreeSpace out;
  std::vector<OpenEnd> ends;
  for (const mapper::Contour& c : contours) {
    for (int k = 0; k < c.NumSegments(); ++k) {
      const Segment s = c.GetSegment(k);
      if (s.length() > 0.0) out.walls.push_back(s);
    }
    if (c.closed && c.NumPoints() >= 3) continue;
    const Eigen::Vector2d in = EndDirection(c.points, false), outward = EndDirection(c.points, true);
    if (in.isZero() || outward.isZero()) continue;  // a point, not a contour with ends
    ends.push_back({c.points.back(), in, c.points.front(), outward});
  }
  out.open_contours = static_cast<int>(ends.size());
  if (ends.empty()) return out;

  const StaticSegmentIndex walls(out.walls);
  const double max_left_turn = kPi - DegToRad(options.min_interior_angle_deg);
  // 2: free space on the consistent side at both joints, no wall crossed, and looking from the
  // frontier into the space it bounds (to its left, at a quarter, half and three quarters of
  // its length) the first wall is seen from its free side: a frontier drawn behind a pillar's
  // face (across its shadow) sees that face's back. 1: all of that but the look. 0: neither.
  auto level = [&](const OpenEnd& a, const OpenEnd& b) {
    const Eigen::Vector2d f = b.start - a.end;
    if (f.norm() <= kTouch) return 2;  // the contours meet: nothing to close
    const double turn_in = Turn(a.end_dir, f), turn_out = Turn(f, b.start_dir);
    if (turn_in > max_left_turn || turn_out > max_left_turn || turn_in >= kPi || turn_out >= kPi) return 0;  // straight back: never
    const Segment frontier(a.end, b.start);
    const Eigen::Vector2d lo = a.end.cwiseMin(b.start), hi = a.end.cwiseMax(b.start);
    for (int w : walls.Query(lo, hi, 0.0))
      if (CrossesAwayFromEnds(frontier, walls.segments()[static_cast<size_t>(w)])) return 0;
    const Eigen::Vector2d left = Eigen::Vector2d(-f.y(), f.x()).normalized();
    for (double t : {0.25, 0.5, 0.75}) {
      const Eigen::Vector2d p = a.end + t * f;
      const std::optional<RayHit> hit = walls.CastRayDir(p, left, options.probe_range);
      if (hit && SignedDistanceToLine(p, walls.segments()[static_cast<size_t>(hit->segment)]) < 0.0) return 1;
    }
    return 2;
  };

  // The candidates of each end: the kCandidates nearest starts, with their level.
  constexpr size_t kCandidates = 24;
  std::vector<Pair> pairs[3];  // by level, shortest first
  std::vector<std::pair<double, int>> by_distance;
  for (size_t i = 0; i < ends.size(); ++i) {
    by_distance.clear();
    for (size_t j = 0; j < ends.size(); ++j)
      by_distance.emplace_back((ends[j].start - ends[i].end).norm(), static_cast<int>(j));
    const size_t n = std::min(kCandidates, by_distance.size());
    std::partial_sort(by_distance.begin(), by_distance.begin() + static_cast<std::ptrdiff_t>(n), by_distance.end());
    for (size_t k = 0; k < n; ++k) {
      const int j = by_distance[k].second;
      const int l = level(ends[i], ends[static_cast<size_t>(j)]);
      if (l > 0) pairs[l].push_back({by_distance[k].first, static_cast<int>(i), j});
    }
  }
  for (int l = 1; l <= 2; ++l)
    std::sort(pairs[l].begin(), pairs[l].end(), [](const Pair& x, const Pair& y) {
      return std::tie(x.length, x.end, x.start) < std::tie(y.length, y.end, y.start);
    });

  std::vector<char> end_done(ends.size(), 0), start_done(ends.size(), 0);
  auto try_join = [&](const Pair& p) {
    const Segment f(ends[static_cast<size_t>(p.end)].end, ends[static_cast<size_t>(p.start)].start);
    if (f.length() > kTouch) {
      for (const Segment& g : out.frontiers)
        if (CrossesAwayFromEnds(f, g) && CrossesAwayFromEnds(g, f)) return;
      out.frontiers.push_back(f);
    }
    end_done[static_cast<size_t>(p.end)] = start_done[static_cast<size_t>(p.start)] = 1;
  };
  for (int l = 2; l >= 1; --l) {
    // Nearest first, each end and each start once.
    for (const Pair& p : pairs[l])
      if (!end_done[static_cast<size_t>(p.end)] && !start_done[static_cast<size_t>(p.start)]) try_join(p);
    // What is left: an end to its nearest start, taken or not; then a start from its nearest end.
    for (const Pair& p : pairs[l])
      if (!end_done[static_cast<size_t>(p.end)]) try_join(p);
    for (const Pair& p : pairs[l])
      if (!start_done[static_cast<size_t>(p.start)]) try_join(p);
  }
  for (size_t i = 0; i < ends.size(); ++i) out.unclosed_ends += (end_done[i] ? 0 : 1) + (start_done[i] ? 0 : 1);
  return out;
}

KnownFreeSpace::KnownFreeSpace(const ContourFreeSpace& space, const FreeSpaceOptions& options) : options_(options) {
  std::vector<Segment> boundary = space.Boundary(false);
  if (!boundary.empty()) index_ = std::make_unique<StaticSegmentIndex>(std::move(boundary));
}

bool KnownFreeSpace::Contains(const Eigen::Vector2d& p) const {
  if (index_ == nullptr || !p.allFinite()) return false;
  int free_votes = 0;
  for (int k = 0; k < options_.probe_rays; ++k) {
    // Off the axes: walls of a mine are often axis-aligned, a ray along one sees nothing useful.
    const double bearing = 0.1234 + 2.0 * kPi * k / options_.probe_rays;
    const std::optional<RayHit> hit = index_->CastRay(p, bearing, options_.probe_range);
    if (hit && SignedDistanceToLine(p, index_->segments()[static_cast<size_t>(hit->segment)]) > 0.0) ++free_votes;
  }
  return 2 * free_votes > options_.probe_rays;
}

}  // namespace minenav
