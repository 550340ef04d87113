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

void DeclareOptions(OptionScope s, MapExpansionOptions& o) {
  s.AddDouble("correspondence_threshold", &o.correspondence_threshold, "m",
              "scan points farther than this from every contour are unmapped (new wall); 0.2 m, twice "
              "the pose's final threshold, so noise on a mapped wall is not taken for a new one",
              0.001, 100.0);
  s.AddDouble("nominal_segment_length", &o.nominal_segment_length, "m",
              "vertex spacing of new contour pieces (fitting then moves the vertices: shorter segments let noise "
              "into the shape, longer ones cut corners)",
              0.01, 100.0);
  s.AddInt("min_new_points", &o.min_new_points,
           "unmatched runs with fewer points are ignored (vertex wedges, noise); 5 [points]", 2, 1000000);
  s.AddDouble("min_new_length", &o.min_new_length, "m",
              "unmatched runs shorter than this along the scan are ignored; 0.3 m", 0.0, 100.0);
  s.AddDouble("end_snap_distance", &o.end_snap_distance, "m",
              "a run continues a contour's end (start) when the matched point next to it lies this close to that "
              "vertex; 1 m, two nominal segments",
              0.0, 100.0);
  s.AddBool("splice_interior", &o.splice_interior,
            "4.8.1: splice runs beside a match on a contour's interior segment into that contour (an object placed "
            "against a wall); false = the static expansion of 4.4 (they become new contours)");
  s.AddDouble("min_splice_length", &o.min_splice_length, "m",
              "shorter unmatched runs beside a contour's interior are not spliced (corners, noise); 0.5 m",
              0.0, 100.0);
  s.AddDouble("max_bypass_ratio", &o.max_bypass_ratio, "1",
              "a case-4 splice into one contour may leave at most this times the run's length of wall behind it "
              "(more: a run across an alcove's mouth, not an object on the wall); 1.5",
              0.001, 1000.0);
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
