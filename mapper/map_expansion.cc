#include "mapper/map_expansion.h"

#include <algorithm>
#include <sstream>

#include "mapper/correspondence.h"

namespace minenav::mapper {

std::string ValidateOptions(const MapExpansionOptions& o) {
  std::ostringstream why;
  if (!(o.correspondence_threshold > 0.0))
    why << "correspondence_threshold must be > 0 m, got " << o.correspondence_threshold;
  else if (!(o.nominal_segment_length > 0.0))
    why << "nominal_segment_length must be > 0 m, got " << o.nominal_segment_length;
  else if (o.min_new_points < 2)
    why << "min_new_points must be >= 2, got " << o.min_new_points;
  else if (!(o.min_new_length >= 0.0) || !(o.end_snap_distance >= 0.0))
    why << "min_new_length and end_snap_distance must be >= 0 m";
  return why.str();
}

std::vector<int> MapExpansionResult::Touched() const {
  std::vector<int> all = created;
  all.insert(all.end(), extended.begin(), extended.end());
  all.insert(all.end(), connected.begin(), connected.end());
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  return all;
}

namespace {

// Does the matched point next to a run sit at the end (or start) of an open contour?
int OpenEndOf(const ContourMap& map, const PointMatch& m, const Eigen::Vector2d& p, bool want_end, double snap) {
  if (!m.matched()) return -1;
  const Contour& c = map.Get(m.segment.contour);
  if (c.closed) return -1;
  const bool on_end_segment = want_end ? m.segment.segment == c.NumSegments() - 1 : m.segment.segment == 0;
  const Eigen::Vector2d& v = want_end ? c.points.back() : c.points.front();
  return on_end_segment || (v - p).norm() <= snap ? c.id : -1;
}

}  // namespace

MapExpansionResult ExpandMap(const PreprocessedScan& scan, const Pose2& pose, ContourMap& map,
                             const MapExpansionOptions& o) {
  MapExpansionResult out;
  const Eigen::Vector2d sensor = pose * scan.sensor_position;
  for (const PartialScan& partial : scan.partial_scans) {
    const std::vector<Eigen::Vector2d> world = ToWorld(partial, pose);
    const int n = static_cast<int>(world.size());
    std::vector<bool> processed(static_cast<size_t>(n), false);
    for (int pass = 0; pass < n; ++pass) {
      const std::vector<PointMatch> m = MatchPoints(world, sensor, map, o.correspondence_threshold);
      // The first unmatched, unprocessed run that is long enough.
      int a = -1, b = -1;
      for (int k = 0; k < n;) {
        if (m[static_cast<size_t>(k)].matched() || processed[static_cast<size_t>(k)]) {
          ++k;
          continue;
        }
        int e = k;
        while (e + 1 < n && !m[static_cast<size_t>(e + 1)].matched() && !processed[static_cast<size_t>(e + 1)]) ++e;
        const std::vector<Eigen::Vector2d> run(world.begin() + k, world.begin() + e + 1);
        if (e - k + 1 >= o.min_new_points && PolylineLength(run, false) >= o.min_new_length) {
          a = k;
          b = e;
          break;
        }
        k = e + 1;
      }
      if (a < 0) break;
      for (int k = a; k <= b; ++k) processed[static_cast<size_t>(k)] = true;

      std::vector<Eigen::Vector2d> run(world.begin() + a, world.begin() + b + 1);
      const int end_of = a > 0 ? OpenEndOf(map, m[static_cast<size_t>(a - 1)], world[static_cast<size_t>(a - 1)],
                                           true, o.end_snap_distance)
                               : -1;
      const int start_of = b + 1 < n ? OpenEndOf(map, m[static_cast<size_t>(b + 1)],
                                                 world[static_cast<size_t>(b + 1)], false, o.end_snap_distance)
                                     : -1;
      const double len = o.nominal_segment_length;
      bool done = false;
      if (end_of >= 0 && start_of >= 0) {
        std::vector<Eigen::Vector2d> path = run;
        path.insert(path.begin(), map.Get(end_of).points.back());
        path.push_back(map.Get(start_of).points.front());
        const std::vector<Eigen::Vector2d> v = PickVertices(path, len);
        const std::vector<Eigen::Vector2d> bridge(v.begin() + 1, v.end() - 1);
        if (end_of != start_of || map.Get(end_of).NumPoints() + static_cast<int>(bridge.size()) >= 3) {
          out.connected.push_back(map.Join(end_of, start_of, bridge));
          done = true;
        }
      }
      if (done) continue;
      if (end_of >= 0) {
        run.insert(run.begin(), map.Get(end_of).points.back());
        std::vector<Eigen::Vector2d> v = PickVertices(run, len);
        map.ExtendEnd(end_of, std::vector<Eigen::Vector2d>(v.begin() + 1, v.end()));
        out.extended.push_back(end_of);
      } else if (start_of >= 0) {
        run.push_back(map.Get(start_of).points.front());
        std::vector<Eigen::Vector2d> v = PickVertices(run, len);
        map.ExtendStart(start_of, std::vector<Eigen::Vector2d>(v.begin(), v.end() - 1));
        out.extended.push_back(start_of);
      } else {
        out.created.push_back(map.Create(PickVertices(run, len)));
      }
    }
  }
  // Joins remove contours: report only ids that still exist.
  auto prune = [&](std::vector<int>& ids) {
    ids.erase(std::remove_if(ids.begin(), ids.end(), [&](int id) { return map.Find(id) == nullptr; }), ids.end());
  };
  prune(out.created);
  prune(out.extended);
  prune(out.connected);
  return out;
}

}  // namespace minenav::mapper
