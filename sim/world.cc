#include "sim/world.h"

#include <algorithm>
#include <cmath>

#include "common/file_io.h"

namespace minenav {

namespace {

constexpr double kMinPieceLength = 1e-9;  // m; shorter pieces of a split segment are dropped

// Crossing count parity of the ray from p towards +x with the edges, half-open in y so a
// ray through a shared vertex of a closed chain counts once.
bool Crosses(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  if ((a.y() > p.y()) == (b.y() > p.y())) return false;
  const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
  return x > p.x();
}

bool InsidePolygon(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& poly) {
  bool inside = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
    if (Crosses(p, poly[j], poly[i])) inside = !inside;
  return inside;
}

// Parameters in (0, 1) along s where it crosses any of `others`.
std::vector<double> SplitParameters(const Segment& s, const std::vector<Segment>& others) {
  std::vector<double> ts{0.0, 1.0};
  const Eigen::Vector2d d = s.b - s.a;
  for (const Segment& o : others) {
    const auto r = RaySegmentIntersection(s.a, d, o);
    if (r && *r > 0.0 && *r < 1.0) ts.push_back(*r);
  }
  std::sort(ts.begin(), ts.end());
  return ts;
}

// Pieces of s between consecutive split parameters, with a flag per piece from `keep`;
// consecutive kept pieces are merged. Returns the kept segments and whether any piece was dropped.
template <typename Keep>
std::vector<Segment> KeptPieces(const Segment& s, const std::vector<double>& ts, Keep keep, bool* dropped) {
  std::vector<Segment> out;
  *dropped = false;
  const Eigen::Vector2d d = s.b - s.a;
  double run_start = -1.0;
  double run_end = -1.0;
  for (size_t k = 0; k + 1 < ts.size(); ++k) {
    const double t0 = ts[k], t1 = ts[k + 1];
    if ((t1 - t0) * d.norm() < kMinPieceLength) continue;
    const Eigen::Vector2d mid = s.a + 0.5 * (t0 + t1) * d;
    if (keep(mid)) {
      if (run_start < 0.0) run_start = t0;
      run_end = t1;
    } else {
      *dropped = true;
      if (run_start >= 0.0) out.emplace_back(s.a + run_start * d, s.a + run_end * d);
      run_start = -1.0;
    }
  }
  if (run_start >= 0.0) {
    // A run covering the whole segment keeps the exact original endpoints.
    if (run_start == 0.0 && run_end == 1.0)
      out.push_back(s);
    else
      out.emplace_back(run_start == 0.0 ? s.a : Eigen::Vector2d(s.a + run_start * d),
                       run_end == 1.0 ? s.b : Eigen::Vector2d(s.a + run_end * d));
  }
  return out;
}

}  // namespace

World::World(const std::vector<Segment>& segments) {
  for (const Segment& s : segments) Insert(s);
  if (!segments.empty()) ++version_;
}

World World::FromJson(const std::string& text, const std::string& source_name) {
  return World(ParseSegmentsJson(text, source_name));
}

World World::Load(const std::string& path) { return World(LoadSegmentsJson(path)); }

std::string World::ToJson() const { return SegmentsToJson(Segments()); }

void World::Save(const std::string& path) const { SaveSegmentsJson(path, Segments()); }

int World::Insert(const Segment& segment) {
  const int id = next_id_++;
  segments_.emplace(id, segment);
  return id;
}

int World::AddSegment(const Segment& segment) {
  const int id = Insert(segment);
  ++version_;
  return id;
}

std::vector<int> World::AddSegments(const std::vector<Segment>& segments) {
  std::vector<int> ids;
  ids.reserve(segments.size());
  for (const Segment& s : segments) ids.push_back(Insert(s));
  if (!segments.empty()) ++version_;
  return ids;
}

std::vector<int> World::AddPolygon(const std::vector<Eigen::Vector2d>& vertices) {
  std::vector<Segment> edges;
  if (vertices.size() >= 2) {
    for (size_t i = 0; i < vertices.size(); ++i) {
      const Eigen::Vector2d& a = vertices[i];
      const Eigen::Vector2d& b = vertices[(i + 1) % vertices.size()];
      if (vertices.size() == 2 && i == 1) break;  // two vertices: a single segment
      edges.emplace_back(a, b);
    }
  }
  return AddSegments(edges);
}

bool World::RemoveSegment(int id) {
  if (segments_.erase(id) == 0) return false;
  ++version_;
  return true;
}

int World::RemoveSegments(const std::vector<int>& ids) {
  int removed = 0;
  for (int id : ids) removed += static_cast<int>(segments_.erase(id));
  if (removed > 0) ++version_;
  return removed;
}

std::vector<int> World::ReplaceSegments(const std::vector<int>& old_ids,
                                        const std::vector<Segment>& new_segments) {
  bool changed = false;
  for (int id : old_ids) changed |= segments_.erase(id) != 0;
  std::vector<int> ids;
  for (const Segment& s : new_segments) ids.push_back(Insert(s));
  if (changed || !ids.empty()) ++version_;
  return ids;
}

int World::CrossingParity(const Eigen::Vector2d& p) const {
  int parity = 0;
  for (const auto& [id, s] : segments_)
    if (Crosses(p, s.a, s.b)) parity ^= 1;
  return parity;
}

bool World::SameSpace(const Eigen::Vector2d& p, const Eigen::Vector2d& free_point) const {
  return CrossingParity(p) == CrossingParity(free_point);
}

CutResult World::CutRegion(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& free_point) {
  CutResult result;
  if (polygon.size() < 3) return result;
  std::vector<Segment> edges;
  for (size_t i = 0; i < polygon.size(); ++i) edges.emplace_back(polygon[i], polygon[(i + 1) % polygon.size()]);

  // The new face first, judged against the world before the cut.
  const std::vector<Segment> before = Segments();
  const int free_parity = CrossingParity(free_point);
  std::vector<Segment> face;
  for (const Segment& e : edges) {
    bool dropped = false;
    // A piece lying on an existing wall (a cut edge flush with it) adds nothing.
    auto on_wall = [&](const Eigen::Vector2d& m) {
      for (const Segment& s : before)
        if (PointToSegmentDistance(m, s) < 1e-9) return true;
      return false;
    };
    const auto pieces = KeptPieces(
        e, SplitParameters(e, before),
        [&](const Eigen::Vector2d& m) { return !on_wall(m) && CrossingParity(m) != free_parity; }, &dropped);
    for (const Segment& p : pieces) {
      face.push_back(p);
      result.new_face_length += p.length();
    }
  }

  // Then the walls inside the polygon go. A wall piece lying on the polygon's outline stays
  // if the side outside the polygon is solid (it still bounds the coal).
  auto keep_wall = [&](const Eigen::Vector2d& m, const Segment& s) {
    bool on_outline = false;
    for (const Segment& e : edges) on_outline = on_outline || PointToSegmentDistance(m, e) < 1e-9;
    if (!on_outline) return !InsidePolygon(m, polygon);
    const Eigen::Vector2d d = (s.b - s.a).normalized();
    const Eigen::Vector2d n(-d.y(), d.x());
    for (double side : {1e-6, -1e-6}) {
      const Eigen::Vector2d probe = m + side * n;
      if (!InsidePolygon(probe, polygon)) return CrossingParity(probe) != free_parity;
    }
    return false;  // both sides inside: cut away
  };
  std::vector<std::pair<int, std::vector<Segment>>> replaced;
  for (const auto& [id, s] : segments_) {
    bool dropped = false;
    const Segment seg = s;
    auto pieces = KeptPieces(s, SplitParameters(s, edges),
                             [&](const Eigen::Vector2d& m) { return keep_wall(m, seg); }, &dropped);
    if (dropped) replaced.emplace_back(id, std::move(pieces));
  }
  for (auto& [id, pieces] : replaced) {
    segments_.erase(id);
    result.removed_ids.push_back(id);
    for (const Segment& p : pieces) result.added_ids.push_back(Insert(p));
  }
  for (const Segment& f : face) result.added_ids.push_back(Insert(f));
  if (!result.removed_ids.empty() || !result.added_ids.empty()) ++version_;
  return result;
}

std::optional<Segment> World::Find(int id) const {
  const auto it = segments_.find(id);
  if (it == segments_.end()) return std::nullopt;
  return it->second;
}

std::vector<Segment> World::Segments() const {
  std::vector<Segment> out;
  out.reserve(segments_.size());
  for (const auto& [id, s] : segments_) out.push_back(s);
  return out;
}

std::vector<WorldSegment> World::Entries() const {
  std::vector<WorldSegment> out;
  out.reserve(segments_.size());
  for (const auto& [id, s] : segments_) out.push_back({id, s});
  return out;
}

std::vector<int> World::Ids() const {
  std::vector<int> out;
  out.reserve(segments_.size());
  for (const auto& [id, s] : segments_) out.push_back(id);
  return out;
}

}  // namespace minenav
