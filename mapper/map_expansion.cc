#include "mapper/map_expansion.h"

#include <algorithm>
#include <sstream>

#include "mapper/correspondence.h"
#include "mapper/map_appearance.h"

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
  else if (!(o.min_splice_length >= 0.0))
    why << "min_splice_length must be >= 0 m, got " << o.min_splice_length;
  else if (!(o.max_bypass_ratio > 0.0))
    why << "max_bypass_ratio must be > 0, got " << o.max_bypass_ratio;
  return why.str();
}

std::vector<int> MapExpansionResult::Touched() const {
  std::vector<int> all = created;
  all.insert(all.end(), extended.begin(), extended.end());
  all.insert(all.end(), connected.begin(), connected.end());
  all.insert(all.end(), spliced.begin(), spliced.end());
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  return all;
}

MapExpansionResult ExpandMap(const PreprocessedScan& scan, const Pose2& pose, ContourMap& map,
                             const MapExpansionOptions& o) {
  MapExpansionResult out;
  const Eigen::Vector2d sensor = pose * scan.sensor_position;
  for (const PartialScan& partial : scan.partial_scans) {
    const std::vector<Eigen::Vector2d> world = ToWorld(partial, pose);
    const int n = static_cast<int>(world.size());
    std::vector<bool> processed(static_cast<size_t>(n), false);
    for (int pass = 0; pass < n; ++pass) {
      // Each edit changes the map: match again, then take the first unmatched, unprocessed
      // run that is long enough.
      const std::vector<PointMatch> m = MatchPoints(world, sensor, map, o.correspondence_threshold);
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

      const RunAnchor left = a > 0 ? LeftAnchor(map, m[static_cast<size_t>(a - 1)], world[static_cast<size_t>(a - 1)],
                                                o.end_snap_distance)
                                   : RunAnchor{};
      const RunAnchor right = b + 1 < n ? RightAnchor(map, m[static_cast<size_t>(b + 1)],
                                                      world[static_cast<size_t>(b + 1)], o.end_snap_distance)
                                        : RunAnchor{};
      const std::vector<Eigen::Vector2d> run(world.begin() + a, world.begin() + b + 1);
      const AppearanceEdit edit = ApplyAppearance(map, run, left, right, o);
      ++out.cases[static_cast<size_t>(edit.case_number)];
      out.spliced.insert(out.spliced.end(), edit.spliced.begin(), edit.spliced.end());
      if (edit.connected)
        out.connected.push_back(edit.contour);
      else if (edit.extended)
        out.extended.push_back(edit.contour);
      else if (edit.contour >= 0)
        out.created.push_back(edit.contour);
    }
  }
  // Joins remove contours: report only ids that still exist.
  auto prune = [&](std::vector<int>& ids) {
    ids.erase(std::remove_if(ids.begin(), ids.end(), [&](int id) { return map.Find(id) == nullptr; }), ids.end());
  };
  prune(out.created);
  prune(out.extended);
  prune(out.connected);
  prune(out.spliced);
  return out;
}

}  // namespace minenav::mapper
