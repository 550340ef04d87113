#pragma once
// Tests and benches only (header-only; links minenav_sim): runs a changing-world scenario
// (sim/changing_world.h, thesis 4.8) through the ContourMapper and judges the map at each of
// the scenario's checks against the judged world and against what must stay.

#include <algorithm>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "common/angle.h"
#include "common/scan.h"
#include "mapper/contour_mapper.h"
#include "evaluation/map_evaluation.h"
#include "sim/changing_world.h"

namespace minenav::mapper::testing {

struct CheckFigures {
  std::string label;
  double deviation_mean = 0.0;      // m, contours vs the judged world's walls
  double deviation_max = 0.0;       // m
  double coverage = 0.0;            // fraction of must_appear within `tolerance` of a contour
  double must_go_m = 0.0;           // m of wall that went and was seen through
  double wrongly_kept_m = 0.0;      // m of it still in the map
  double must_stay_m = 0.0;         // m of wall seen earlier and still there
  double wrongly_removed_m = 0.0;   // m of it missing from the map
  double hidden_m = 0.0;            // m of must_stay that is hidden now
  double hidden_removed_m = 0.0;    // m of the hidden part missing from the map
  int contours = 0;
};

inline bool NearMap(const ContourMap& map, const Eigen::Vector2d& p, double tolerance) {
  bool hit = false;
  map.ForEachSegmentNear(p, tolerance, [&](const SegmentRef& r) {
    if (!hit && PointToSegmentDistance(p, map.Get(r.contour).GetSegment(r.segment)) <= tolerance) hit = true;
  });
  return hit;
}

inline CheckFigures JudgeMap(const ContourMap& map, const ChangingWorldScenario& sc, const ScenarioCheck& c,
                             double tolerance = 0.1) {
  CheckFigures f;
  f.label = c.label;
  const MapDeviation dev = ContourDeviation(map, sc.worlds[static_cast<size_t>(c.world)]);
  f.deviation_mean = dev.mean;
  f.deviation_max = dev.max;
  int covered = 0;
  for (const WallSample& s : c.must_appear) covered += NearMap(map, s.point, tolerance) ? 1 : 0;
  f.coverage = c.must_appear.empty() ? 1.0 : static_cast<double>(covered) / static_cast<double>(c.must_appear.size());
  for (const WallSample& s : c.must_go) {
    f.must_go_m += sc.sample_step;
    if (NearMap(map, s.point, tolerance)) f.wrongly_kept_m += sc.sample_step;
  }
  for (const WallSample& s : c.must_stay) {
    const bool missing = !NearMap(map, s.point, tolerance);
    f.must_stay_m += sc.sample_step;
    f.wrongly_removed_m += missing ? sc.sample_step : 0.0;
    if (s.hidden) {
      f.hidden_m += sc.sample_step;
      f.hidden_removed_m += missing ? sc.sample_step : 0.0;
    }
  }
  f.contours = map.NumContours();
  return f;
}

// Simulates the scan station k sees in `world` from its true pose.
using ScanFunction = std::function<LadarScan(const std::vector<Segment>& world, const Pose2& pose, int k)>;

struct ScenarioRun {
  std::vector<CheckFigures> checks;
  int refused = 0;
  double max_pose_error = 0.0;       // m
  double max_heading_error = 0.0;    // rad
  std::vector<ContourMap> maps;      // the map at each check
  std::vector<std::string> log;      // one line per insert
};

// Inserts every station's scan in order (the first at its true pose, the others from truth
// plus Gaussian noise) and judges the map at each check.
inline ScenarioRun RunScenario(const ChangingWorldScenario& sc, const ContourMapperOptions& options,
                               const ScanFunction& scan_of, double sigma_xy = 0.1, double sigma_theta = 0.02,
                               unsigned seed = 1) {
  ScenarioRun out;
  ContourMapper cm(options);
  std::mt19937 rng(seed);
  std::normal_distribution<double> nxy(0.0, sigma_xy), nth(0.0, sigma_theta);
  for (size_t k = 0; k < sc.stations.size(); ++k) {
    const Station& st = sc.stations[k];
    const Pose2 truth = st.pose;
    const double dx = nxy(rng), dy = nxy(rng), dt = nth(rng);
    const Pose2 initial = k == 0 ? truth : Pose2(truth.x + dx, truth.y + dy, truth.theta + dt);
    const InsertResult r =
        cm.InsertScan(scan_of(sc.worlds[static_cast<size_t>(st.world)], truth, static_cast<int>(k)), initial);
    out.log.push_back("station " + std::to_string(k) + " (world " + std::to_string(st.world) + "): " +
                      (r.accepted ? "" : "REFUSED: ") + r.reason);
    if (!r.accepted) {
      ++out.refused;
    } else {
      out.max_pose_error = std::max(out.max_pose_error, TranslationDistance(r.pose, truth));
      out.max_heading_error = std::max(out.max_heading_error, HeadingDistance(r.pose, truth));
    }
    for (const ScenarioCheck& c : sc.checks)
      if (c.after_station == static_cast<int>(k)) {
        out.checks.push_back(JudgeMap(cm.map(), sc, c));
        out.maps.push_back(cm.map());
      }
  }
  return out;
}

}  // namespace minenav::mapper::testing
