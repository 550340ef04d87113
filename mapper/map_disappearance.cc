#include "mapper/map_disappearance.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <sstream>
#include <utility>

#include "common/angle.h"
#include "mapper/correspondence.h"

namespace minenav::mapper {

namespace {

using Vec = Eigen::Vector2d;
using Interval = std::pair<double, double>;

double Cross(const Vec& a, const Vec& b) { return a.x() * b.y() - a.y() * b.x(); }

// One triangle of coverage: the sensor and two beams, bearings b0 < b1 (unwrapped, widened
// by half the divergence each), reaching ranges r0, r1; p0, p1 the scan points.
struct Triangle {
  double b0 = 0.0, b1 = 0.0, r0 = 0.0, r1 = 0.0;
  Vec p0 = Vec::Zero(), p1 = Vec::Zero();
};

constexpr int kBins = 4096;
int Bin(double bearing) {
  const double u = (NormalizeAngle(bearing) + kPi) / (2.0 * kPi);
  return std::clamp(static_cast<int>(u * kBins), 0, kBins - 1);
}

// Bins covered by the bearing interval [lo, lo + width].
template <typename F>
void ForBins(double lo, double width, F&& f) {
  const int first = Bin(lo);
  const int count = std::min(kBins, static_cast<int>(std::ceil(width / (2.0 * kPi) * kBins)) + 1);
  for (int i = 0; i < count; ++i) f((first + i) % kBins);
}

// Where the beam at `bearing` from s crosses segment a-b: parameter t on the segment, range
// rho along the beam. False when it misses or the view is more glancing than min_sine.
bool Crossing(const Vec& s, double bearing, const Vec& a, const Vec& b, double min_sine, double* t, double* rho) {
  const Vec d(std::cos(bearing), std::sin(bearing));
  const Vec e = b - a;
  const double denom = Cross(d, e);
  const double len = e.norm();
  if (len <= 0.0 || std::abs(denom) < min_sine * len || std::abs(denom) < 1e-12) return false;
  const Vec w = a - s;
  *rho = Cross(w, e) / denom;
  *t = Cross(w, d) / denom;
  return *rho > 0.0 && *t >= 0.0 && *t <= 1.0;
}

// The sub-polyline of `path` (cumulative arc `arc`) between arc positions u0 < u1.
std::vector<Vec> Piece(const std::vector<Vec>& path, const std::vector<double>& arc, double u0, double u1) {
  auto at = [&](double u) {
    const size_t k = static_cast<size_t>(
        std::clamp<long>(std::upper_bound(arc.begin(), arc.end(), u) - arc.begin() - 1, 0, static_cast<long>(arc.size()) - 2));
    const double len = arc[k + 1] - arc[k];
    const double f = len > 0.0 ? (u - arc[k]) / len : 0.0;
    return Vec(path[k] + std::clamp(f, 0.0, 1.0) * (path[k + 1] - path[k]));
  };
  std::vector<Vec> out{at(u0)};
  for (size_t k = 0; k < path.size(); ++k)
    if (arc[k] > u0 + 1e-9 && arc[k] < u1 - 1e-9) out.push_back(path[k]);
  out.push_back(at(u1));
  return out;
}

}  // namespace

std::string ValidateOptions(const MapDisappearanceOptions& o) {
  std::ostringstream why;
  if (!(o.beam_divergence >= 0.0 && o.beam_divergence < 0.1))
    why << "beam_divergence must be in [0, 0.1) rad, got " << o.beam_divergence;
  else if (!(o.correspondence_threshold > 0.0))
    why << "correspondence_threshold must be > 0 m, got " << o.correspondence_threshold;
  else if (!(o.min_view_angle >= 0.0 && o.min_view_angle < 1.5))
    why << "min_view_angle must be in [0, 1.5) rad, got " << o.min_view_angle;
  else if (!(o.min_removed_length >= 0.0) || !(o.min_piece_length >= 0.0))
    why << "min_removed_length and min_piece_length must be >= 0 m";
  return why.str();
}

void DeclareOptions(OptionScope s, MapDisappearanceOptions& o) {
  s.AddBool("enabled", &o.enabled,
            "4.8.2: remove contour parts the scan sees through (triangles of coverage); on, a static "
            "survey keeps its accuracy (mapper/README.md, Changing worlds)");
  s.AddDouble("beam_divergence", &o.beam_divergence, "rad",
              "full beam divergence widening each triangle of coverage by half on either side; 0.003 is "
              "the Typhoon's, the Cyclone's is 0.004 (sensor_driver/ladar_model.h)",
              0.0, 0.1);
  s.AddDouble("correspondence_threshold", &o.correspondence_threshold, "m",
              "a segment must lie this far in front of both scan points (and this far from them) to be seen "
              "through; 0.1 m, the pose's final threshold",
              0.001, 100.0);
  s.AddDouble("min_view_angle", &o.min_view_angle, "rad",
              "beams meeting a contour more glancingly than this remove nothing from it (a wall looked along is "
              "not seen through); 0.35 rad (20 degrees)",
              0.0, 1.57);
  s.AddDouble("min_removed_length", &o.min_removed_length, "m",
              "removed stretches shorter than this along the contour are kept: fitted contours end a few cm past "
              "true corners, and rays past a corner would nibble it scan after scan; 0.3 m",
              0.0, 100.0);
  s.AddDouble("min_piece_length", &o.min_piece_length, "m",
              "pieces of a cut contour shorter than this go too (the last glancing bits of an object seen "
              "through; 0.3 m left bits of a parked machine); 0.6 m",
              0.0, 100.0);
}

MapDisappearanceResult RemoveDisappeared(const PreprocessedScan& scan, const Pose2& pose, ContourMap& map,
                                         const MapDisappearanceOptions& o) {
  MapDisappearanceResult out;
  const Vec sensor = pose * scan.sensor_position;
  const double half = 0.5 * o.beam_divergence;

  // The triangles of coverage, binned by bearing.
  std::vector<Triangle> triangles;
  double reach = 0.0;
  auto add = [&](const Vec& p, const Vec& q, double r0, double r1) {
    const double b0 = std::atan2(p.y() - sensor.y(), p.x() - sensor.x());
    const double step = NormalizeAngle(std::atan2(q.y() - sensor.y(), q.x() - sensor.x()) - b0);
    if (!(step > 0.0 && step < 0.5)) return;  // not counter-clockwise neighbours
    triangles.push_back({b0 - half, b0 + step + half, r0, r1, p, q});
    reach = std::max({reach, r0, r1});
  };
  std::vector<std::vector<Vec>> world;
  for (const PartialScan& partial : scan.partial_scans) world.push_back(ToWorld(partial, pose));
  for (size_t k = 0; k < world.size(); ++k) {
    const std::vector<Vec>& w = world[k];
    for (size_t i = 0; i + 1 < w.size(); ++i) add(w[i], w[i + 1], (w[i] - sensor).norm(), (w[i + 1] - sensor).norm());
    // Neighbouring readings across a discontinuity: covered out to the nearer range.
    if (k + 1 < world.size() && !w.empty() && !world[k + 1].empty() &&
        scan.partial_scans[k].last_index + 1 == scan.partial_scans[k + 1].first_index) {
      const double r = std::min((w.back() - sensor).norm(), (world[k + 1].front() - sensor).norm());
      add(w.back(), world[k + 1].front(), r, r);
    }
  }
  if (triangles.empty()) return out;
  std::vector<std::vector<int>> bins(kBins);
  for (size_t i = 0; i < triangles.size(); ++i)
    ForBins(triangles[i].b0, triangles[i].b1 - triangles[i].b0, [&](int b) { bins[static_cast<size_t>(b)].push_back(static_cast<int>(i)); });

  // Where each triangle's two sides cross contour segments in front of their scan points,
  // not glancingly, as arc-length positions along the contour.
  const double min_sine = std::sin(o.min_view_angle);
  const double thr = o.correspondence_threshold;
  struct SideCrossing {
    int triangle = 0, contour = 0, side = 0;
    double arc = 0.0;
    Vec at = Vec::Zero();
    bool operator<(const SideCrossing& other) const {
      return std::tie(triangle, contour, side, arc) < std::tie(other.triangle, other.contour, other.side, other.arc);
    }
  };
  std::vector<SideCrossing> crossings;
  std::vector<int> stamp(triangles.size(), -1);
  int stamp_id = 0;
  for (const auto& [contour_id, c] : map.contours()) {
    const int id = contour_id;  // a copy: clang 14 (the fuzz build) cannot capture a structured binding
    double arc_start = 0.0;  // arc length at the start of segment k
    for (int k = 0; k < c.NumSegments(); ++k, ++stamp_id) {
      const Segment s = c.GetSegment(k);
      const double length = s.length();
      const double arc_here = arc_start;
      arc_start += length;
      if (PointToSegmentDistance(sensor, s) > reach) continue;
      const double a0 = std::atan2(s.a.y() - sensor.y(), s.a.x() - sensor.x());
      const double span = NormalizeAngle(std::atan2(s.b.y() - sensor.y(), s.b.x() - sensor.x()) - a0);
      const double lo = span >= 0.0 ? a0 : a0 + span;
      ForBins(lo, std::abs(span), [&](int b) {
        for (const int ti : bins[static_cast<size_t>(b)]) {
          if (stamp[static_cast<size_t>(ti)] == stamp_id) continue;
          stamp[static_cast<size_t>(ti)] = stamp_id;
          const Triangle& tr = triangles[static_cast<size_t>(ti)];
          for (int side = 0; side < 2; ++side) {
            double t, rho;
            const double bearing = side == 0 ? tr.b0 : tr.b1, range = side == 0 ? tr.r0 : tr.r1;
            const Vec& p = side == 0 ? tr.p0 : tr.p1;
            if (!Crossing(sensor, bearing, s.a, s.b, min_sine, &t, &rho)) continue;
            if (rho > range - thr) continue;                        // not in front of the point
            if (PointToSegmentDistance(p, s) <= thr) continue;      // the point corresponds to it
            crossings.push_back({ti, id, side, arc_here + t * length, s.a + t * (s.b - s.a)});
          }
        }
      });
    }
  }
  std::sort(crossings.begin(), crossings.end());

  // A triangle crossed on both sides by one contour removes the stretch between the two
  // crossings (usually on one segment; across a vertex when the contour bends inside the
  // triangle). The stretch must be about as short as the chord between the crossings, else
  // the contour leaves the triangle in between (crossings far apart along it).
  std::map<int, std::vector<Interval>> removed;
  for (size_t i = 0; i < crossings.size();) {
    size_t j = i;
    while (j < crossings.size() && crossings[j].triangle == crossings[i].triangle &&
           crossings[j].contour == crossings[i].contour)
      ++j;
    const Contour& c = map.Get(crossings[i].contour);
    const double total = c.Length();
    for (size_t a = i; a < j; ++a)
      for (size_t b = i; b < j; ++b) {
        if (crossings[a].side != 0 || crossings[b].side != 1) continue;
        double lo = std::min(crossings[a].arc, crossings[b].arc), hi = std::max(crossings[a].arc, crossings[b].arc);
        bool wraps = false;
        if (c.closed && hi - lo > 0.5 * total) {  // the short way round passes the start
          std::swap(lo, hi);
          hi += total;
          wraps = true;
        }
        const double chord = (crossings[a].at - crossings[b].at).norm();
        if (hi - lo > 1.5 * chord + 1e-6) continue;
        std::vector<Interval>& list = removed[c.id];
        if (wraps) {
          list.push_back({lo, total});
          list.push_back({0.0, hi - total});
        } else {
          list.push_back({lo, hi});
        }
      }
    i = j;
  }

  for (auto& [id, cuts] : removed) {
    const Contour c = map.Get(id);
    // Arc-length positions, with the path doubled for closed contours (pieces may wrap).
    std::vector<Vec> path = c.points;
    if (c.closed) {
      path.insert(path.end(), c.points.begin(), c.points.end());
      path.push_back(c.points.front());
    }
    std::vector<double> arc(path.size(), 0.0);
    for (size_t k = 1; k < path.size(); ++k) arc[k] = arc[k - 1] + (path[k] - path[k - 1]).norm();
    const double total = c.Length();
    std::sort(cuts.begin(), cuts.end());
    std::vector<Interval> merged;
    for (const Interval& iv : cuts) {
      if (!merged.empty() && iv.first <= merged.back().second + 1e-6)
        merged.back().second = std::max(merged.back().second, iv.second);
      else
        merged.push_back(iv);
    }
    if (c.closed && merged.size() > 1 && merged.front().first <= 1e-6 && merged.back().second >= total - 1e-6) {
      merged.back().second = total + merged.front().second;  // one stretch across the start
      merged.erase(merged.begin());
    }
    merged.erase(std::remove_if(merged.begin(), merged.end(),
                                [&](const Interval& iv) { return iv.second - iv.first < o.min_removed_length; }),
                 merged.end());
    if (merged.empty()) continue;

    // What stays: the complement of the removed stretches.
    std::vector<Interval> keep;
    if (c.closed) {
      for (size_t i = 0; i < merged.size(); ++i) {
        const double from = merged[i].second;
        const double to = i + 1 < merged.size() ? merged[i + 1].first : merged.front().first + total;
        keep.push_back({from, to});
      }
    } else {
      double from = 0.0;
      for (const Interval& iv : merged) {
        keep.push_back({from, iv.first});
        from = iv.second;
      }
      keep.push_back({from, total});
    }
    std::vector<std::vector<Vec>> pieces;
    double kept = 0.0;
    for (const Interval& iv : keep) {
      if (iv.second - iv.first < std::max(o.min_piece_length, 1e-6)) continue;
      pieces.push_back(Piece(path, arc, iv.first, iv.second));
      kept += iv.second - iv.first;
    }
    out.removed_length += total - kept;
    if (pieces.empty()) {
      map.Remove(id);
      ++out.contours_removed;
      continue;
    }
    if (c.closed) map.Detach(id, 0);  // opens it, keeping the id
    map.SetPoints(id, std::move(pieces.front()));
    out.changed.push_back(id);
    for (size_t i = 1; i < pieces.size(); ++i) out.changed.push_back(map.Create(std::move(pieces[i])));
  }
  return out;
}

}  // namespace minenav::mapper
