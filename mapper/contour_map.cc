#include "mapper/contour_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace minenav::mapper {

namespace {
void CheckSize(const std::vector<Eigen::Vector2d>& points, bool closed) {
  if (points.size() < (closed ? 3u : 2u))
    throw std::logic_error("contour needs at least " + std::string(closed ? "3" : "2") + " points, got " +
                           std::to_string(points.size()));
}
}  // namespace

const Contour* ContourMap::Find(int id) const {
  const auto it = contours_.find(id);
  return it == contours_.end() ? nullptr : &it->second;
}

const Contour& ContourMap::Get(int id) const {
  const Contour* c = Find(id);
  if (!c) throw std::logic_error("no contour " + std::to_string(id));
  return *c;
}

std::vector<SegmentRef> ContourMap::SegmentsNear(const Eigen::Vector2d& p, double radius) const {
  const std::vector<SegmentId> ids = grid_.QueryPoint(p, radius);
  std::vector<SegmentRef> out;
  out.reserve(ids.size());
  for (const SegmentId& id : ids) out.push_back({id.group, id.index});
  return out;
}

void ContourMap::Reindex(const Contour& c) {
  std::vector<Segment> segments;
  segments.reserve(static_cast<size_t>(c.NumSegments()));
  for (int k = 0; k < c.NumSegments(); ++k) segments.push_back(c.GetSegment(k));
  grid_.Insert(c.id, segments);
}

Contour& ContourMap::Mutable(int id) {
  const auto it = contours_.find(id);
  if (it == contours_.end()) throw std::logic_error("no contour " + std::to_string(id));
  return it->second;
}

std::vector<int> ContourMap::Ids() const {
  std::vector<int> ids;
  ids.reserve(contours_.size());
  for (const auto& [id, c] : contours_) ids.push_back(id);
  return ids;
}

int ContourMap::NumSegments() const {
  int n = 0;
  for (const auto& [id, c] : contours_) n += c.NumSegments();
  return n;
}

double ContourMap::TotalLength() const {
  double total = 0.0;
  for (const auto& [id, c] : contours_) total += c.Length();
  return total;
}

int ContourMap::Create(std::vector<Eigen::Vector2d> points, bool closed) {
  CheckSize(points, closed);
  Contour c;
  c.id = next_id_++;
  c.closed = closed;
  c.points = std::move(points);
  Reindex(c);
  const int id = c.id;
  contours_.emplace(id, std::move(c));
  return id;
}

void ContourMap::SetPoints(int id, std::vector<Eigen::Vector2d> points) {
  Contour& c = Mutable(id);
  CheckSize(points, c.closed);
  c.points = std::move(points);
  Reindex(c);
}

void ContourMap::Remove(int id) {
  grid_.Remove(id);
  contours_.erase(id);
}

void ContourMap::Clear() {
  contours_.clear();
  grid_.Clear();
}

int ContourMap::Cut(int id, int segment, const Eigen::Vector2d& point) {
  Contour& c = Mutable(id);
  if (segment < 0 || segment >= c.NumSegments()) throw std::logic_error("Cut: no segment " + std::to_string(segment));
  const int at = segment + 1;  // for the closing segment of a closed contour this appends
  c.points.insert(c.points.begin() + at, point);
  Reindex(c);
  return at;
}

std::optional<int> ContourMap::Detach(int id, int vertex) {
  Contour& c = Mutable(id);
  if (vertex < 0 || vertex >= c.NumPoints()) throw std::logic_error("Detach: no vertex " + std::to_string(vertex));
  if (c.closed) {
    std::rotate(c.points.begin(), c.points.begin() + vertex, c.points.end());
    c.points.push_back(c.points.front());
    c.closed = false;
    Reindex(c);
    return id;
  }
  if (vertex == 0 || vertex == c.NumPoints() - 1) return std::nullopt;
  std::vector<Eigen::Vector2d> tail(c.points.begin() + vertex, c.points.end());
  c.points.resize(static_cast<size_t>(vertex) + 1);
  Reindex(c);
  return Create(std::move(tail), false);
}

void ContourMap::ExtendEnd(int id, const std::vector<Eigen::Vector2d>& points) {
  Contour& c = Mutable(id);
  if (c.closed) throw std::logic_error("ExtendEnd on a closed contour");
  c.points.insert(c.points.end(), points.begin(), points.end());
  Reindex(c);
}

void ContourMap::ExtendStart(int id, const std::vector<Eigen::Vector2d>& points) {
  Contour& c = Mutable(id);
  if (c.closed) throw std::logic_error("ExtendStart on a closed contour");
  c.points.insert(c.points.begin(), points.begin(), points.end());
  Reindex(c);
}

int ContourMap::Join(int first, int second, const std::vector<Eigen::Vector2d>& bridge) {
  Contour& a = Mutable(first);
  if (a.closed) throw std::logic_error("Join: contour is closed");
  if (first == second) {
    a.points.insert(a.points.end(), bridge.begin(), bridge.end());
    if (a.points.size() < 3) throw std::logic_error("Join: closing needs >= 3 points");
    a.closed = true;
    Reindex(a);
    return first;
  }
  Contour& b = Mutable(second);
  if (b.closed) throw std::logic_error("Join: contour is closed");
  a.points.insert(a.points.end(), bridge.begin(), bridge.end());
  a.points.insert(a.points.end(), b.points.begin(), b.points.end());
  Remove(second);
  Contour& merged = Mutable(first);
  Reindex(merged);
  return first;
}

ContourMap::SpliceResult ContourMap::Splice(int target, int segment, const Eigen::Vector2d& point, int attach,
                                            SpliceSide side) {
  if (target == attach) throw std::logic_error("Splice: a contour onto itself");
  if (Get(attach).closed) throw std::logic_error("Splice: attached contour is closed");
  const int v = Cut(target, segment, point);
  SpliceResult out;
  const bool was_closed = Get(target).closed;
  const std::optional<int> tail = Detach(target, v);
  if (was_closed) {
    // target now runs cut point .. cut point.
    if (side == SpliceSide::kAttachStartAfterCut) {
      out.joined = Join(target, attach);
    } else {
      out.joined = Join(attach, target);
    }
    return out;
  }
  if (side == SpliceSide::kAttachStartAfterCut) {
    out.joined = Join(target, attach);  // [start .. p] + attach
    out.remainder = tail.value_or(-1);
  } else {
    out.joined = Join(attach, tail.value());  // attach + [p .. end]
    out.remainder = target;
  }
  return out;
}

int ContourMap::RemoveDegenerateSegments(int id, double min_length) {
  Contour& c = Mutable(id);
  std::vector<Eigen::Vector2d>& p = c.points;
  int removed = 0;
  bool changed = true;
  while (changed && p.size() >= 2) {
    changed = false;
    const int n = static_cast<int>(p.size());
    const int segs = c.NumSegments();
    for (int k = 0; k < segs; ++k) {
      const int i = k, j = (k + 1) % n;
      if ((p[static_cast<size_t>(j)] - p[static_cast<size_t>(i)]).norm() >= min_length) continue;
      if (!c.closed && n <= 2) break;
      if (c.closed && n <= 3) break;
      if (!c.closed && j == n - 1) {
        p.erase(p.begin() + i);  // keep the end vertex where it is
      } else if (!c.closed && i == 0) {
        p.erase(p.begin() + j);  // keep the start vertex
      } else {
        p[static_cast<size_t>(i)] = 0.5 * (p[static_cast<size_t>(i)] + p[static_cast<size_t>(j)]);
        p.erase(p.begin() + j);
      }
      ++removed;
      changed = true;
      break;
    }
  }
  if (p.size() < (c.closed ? 3u : 2u) ||
      (p.size() == 2 && (p[1] - p[0]).norm() < min_length)) {
    Remove(id);
    return removed;
  }
  Reindex(c);
  return removed;
}

int ContourMap::RemoveSpikes(int id, double max_turn) {
  Contour& c = Mutable(id);
  std::vector<Eigen::Vector2d>& p = c.points;
  const double min_cos = std::cos(max_turn);
  int removed = 0;
  bool changed = true;
  while (changed && p.size() >= (c.closed ? 4u : 3u)) {
    changed = false;
    const int n = static_cast<int>(p.size());
    for (int v = c.closed ? 0 : 1; v < (c.closed ? n : n - 1); ++v) {
      const Eigen::Vector2d in = p[static_cast<size_t>(v)] - p[static_cast<size_t>((v + n - 1) % n)];
      const Eigen::Vector2d out = p[static_cast<size_t>((v + 1) % n)] - p[static_cast<size_t>(v)];
      const double norms = in.norm() * out.norm();
      if (norms <= 0.0 || in.dot(out) / norms >= min_cos) continue;
      p.erase(p.begin() + v);
      ++removed;
      changed = true;
      break;
    }
  }
  Reindex(c);
  return removed;
}

void ContourMap::Resample(int id, double nominal_length) {
  Contour& c = Mutable(id);
  c.points = ResamplePolyline(c.points, c.closed, nominal_length);
  Reindex(c);
}

}  // namespace minenav::mapper
