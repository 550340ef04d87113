// Thesis 3.6 measured: the feature-based (FPE) and the iconic (IPE, surveyed-map mode)
// estimators side by side on the same simulated scans and initial estimates.
//   1. Sensitivity to the initial estimate: success rate for initial heading errors up to
//      45 deg and position errors up to 1 m (the thesis: FPE "does not require a good
//      initial heading estimate"). FPE runs with its matching bounds opened to the error
//      it is told to expect (angerr 50 deg, poserr 1.2 m); IPE with its defaults.
//   2. Points per scan needed: 256 .. 4096-point Cyclone scans.
//   3. Accuracy and time per estimate (2048 points).
//   4. Robustness to map errors: a wall moved by 0.3 m, a wall missing from the map.
//   5. The unstructured mine (5.2.1 synthetic room-and-pillar, 5.3 research mine) with a
//      Typhoon: how many features FPE finds there, and what that does to the estimates.
// Success: converged and within 10 cm and 1 deg of the truth.
#include <cstdio>
#include <functional>
#include <random>

#include "bench/fpe_bench_util.h"

using namespace minenav;

namespace {

struct Tally {
  int trials = 0, converged = 0, success = 0;
  std::vector<double> pos, head, time, corners, lines, matches;
  void Add(const fpeb::Outcome& o) {
    ++trials;
    converged += o.converged;
    success += o.success();
    if (o.converged) {
      pos.push_back(o.position_error);
      head.push_back(std::abs(o.heading_error));
    }
    time.push_back(o.seconds);
  }
  double SuccessPct() const { return fpeb::Percent(success, trials); }
  // Converged but wrong: the failure that matters most.
  int WrongConverged() const { return converged - success; }
  nlohmann::json Json() const {
    return {{"trials", trials}, {"converged", converged}, {"success", success},
            {"success_pct", SuccessPct()}, {"converged_but_wrong", WrongConverged()},
            {"position_err_cm_median", 100 * fpeb::Median(pos)}, {"position_err_cm_max", 100 * fpeb::Max(pos)},
            {"heading_err_deg_median", RadToDeg(fpeb::Median(head))}, {"heading_err_deg_max", RadToDeg(fpeb::Max(head))},
            {"time_ms_median", 1e3 * fpeb::Median(time)},
            {"sensed_corners_median", fpeb::Median(corners)}, {"sensed_lines_median", fpeb::Median(lines)},
            {"matches_median", fpeb::Median(matches)}};
  }
};

struct Scene {
  std::vector<Segment> map;    // what the estimators are given
  std::vector<Segment> world;  // what the sensor sees
  std::vector<Pose2> stations;
};

// Runs both estimators over every station of each scene, `draws` noise draws each.
void RunBoth(const std::vector<Scene>& scenes, const LadarModel& model, double pos_err, double head_err,
             bool exact_magnitude, const FeaturePoseEstimatorOptions& fpe_options, Tally* fpe_tally,
             Tally* ipe_tally, uint64_t seed) {
  std::mt19937 rng(static_cast<unsigned>(seed));
  for (size_t s = 0; s < scenes.size(); ++s) {
    const Scene& sc = scenes[s];
    const FeaturePoseEstimator fpe(sc.map, fpe_options);
    IconicEstimator ipe(fpeb::SurveyedIpeOptions());
    const std::string problem = ipe.SetMap(sc.map);
    if (!problem.empty()) {
      std::fprintf(stderr, "IPE map: %s\n", problem.c_str());
      std::exit(3);
    }
    const LadarSimulator sim(model, seed * 1000 + s);
    const StaticSegmentIndex world(sc.world);
    for (size_t k = 0; k < sc.stations.size(); ++k) {
      const Pose2& truth = sc.stations[k];
      const LadarScan scan = sim.Simulate(world, truth, Pose2(), static_cast<int64_t>(k), static_cast<int64_t>(k));
      const Pose2 initial = fpeb::Perturb(truth, pos_err, head_err, &rng, exact_magnitude);
      FeaturePoseResult detail;
      fpe_tally->Add(fpeb::RunFpe(fpe, scan, initial, truth, &detail));
      fpe_tally->corners.push_back(detail.sensed_corners);
      fpe_tally->lines.push_back(detail.sensed_lines);
      fpe_tally->matches.push_back(detail.matches);
      ipe_tally->Add(fpeb::RunIpe(&ipe, scan, initial, truth));
    }
  }
}

std::vector<Scene> MockupScenes(int draws, const std::function<void(std::vector<Segment>*)>& edit_map = {}) {
  std::vector<Scene> scenes;
  for (int d = 0; d < draws; ++d) {
    const MockupWorld m = GenerateIndoorMockup(static_cast<uint64_t>(d + 1));
    Scene sc;
    sc.map = m.map;
    if (edit_map) edit_map(&sc.map);
    sc.world = m.World();
    for (const Station& st : m.stations) sc.stations.push_back(st.pose);
    scenes.push_back(sc);
  }
  return scenes;
}

bool Near(const Segment& s, double x1, double y1, double x2, double y2) {
  return ((s.a - Eigen::Vector2d(x1, y1)).norm() < 1e-6 && (s.b - Eigen::Vector2d(x2, y2)).norm() < 1e-6) ||
         ((s.b - Eigen::Vector2d(x1, y1)).norm() < 1e-6 && (s.a - Eigen::Vector2d(x2, y2)).norm() < 1e-6);
}

void PrintRow(const char* label, const Tally& f, const Tally& i) {
  std::printf("%-34s | FPE %5.1f%% (%2d wrong) %6.1f cm %5.2f deg %7.2f ms | IPE %5.1f%% (%2d wrong) %6.1f cm %5.2f deg %7.2f ms\n",
              label, f.SuccessPct(), f.WrongConverged(), 100 * fpeb::Median(f.pos), RadToDeg(fpeb::Median(f.head)),
              1e3 * fpeb::Median(f.time), i.SuccessPct(), i.WrongConverged(), 100 * fpeb::Median(i.pos),
              RadToDeg(fpeb::Median(i.head)), 1e3 * fpeb::Median(i.time));
}

}  // namespace

int main(int argc, char** argv) {
  const auto args = fpeb::ParseBenchArgs(argc, argv, "usage: fpe_comparison [--json-out FILE] [--quick]");
  const int draws = args.quick ? 1 : 3;
  nlohmann::json report;
  std::printf("Columns: success rate (converged but wrong), median position error, median heading error, median time.\n");

  // 1. Sensitivity to the initial estimate.
  FeaturePoseEstimatorOptions wide;
  wide.matching.angerr = DegToRad(50.0);
  wide.matching.poserr = 1.2;
  const std::vector<Scene> mockup = MockupScenes(draws);
  std::printf("\n1. Sensitivity to the initial estimate (mockup, 2048-point Cyclone, %d scans per cell; FPE angerr 50 deg, poserr 1.2 m)\n",
              draws * 16);
  nlohmann::json sens = nlohmann::json::array();
  for (double pos : {0.0, 0.5, 1.0}) {
    for (double head : {0.0, 5.0, 10.0, 20.0, 30.0, 45.0}) {
      Tally f, i;
      RunBoth(mockup, fpeb::MockupCyclone(2048), pos, DegToRad(head), true, wide, &f, &i, 11);
      char label[64];
      std::snprintf(label, sizeof label, "init error %.1f m, %4.1f deg", pos, head);
      PrintRow(label, f, i);
      sens.push_back({{"position_error_m", pos}, {"heading_error_deg", head}, {"fpe", f.Json()}, {"ipe", i.Json()}});
    }
  }
  report["sensitivity"] = sens;

  // 2 + 3. Points per scan; accuracy and time at 2048.
  std::printf("\n2. Points per scan (mockup, initial error up to 0.5 m and 4 deg; FPE thesis parameters)\n");
  nlohmann::json pts = nlohmann::json::array();
  for (int n : {256, 512, 1024, 2048, 4096}) {
    Tally f, i;
    RunBoth(mockup, fpeb::MockupCyclone(n), 0.5, DegToRad(4.0), false, FeaturePoseEstimatorOptions(), &f, &i, 12);
    char label[64];
    std::snprintf(label, sizeof label, "%4d points", n);
    PrintRow(label, f, i);
    pts.push_back({{"points", n}, {"fpe", f.Json()}, {"ipe", i.Json()}});
  }
  report["points_per_scan"] = pts;

  // 4. Map errors.
  std::printf("\n4. Robustness to map errors (mockup, 2048 points, initial error up to 0.5 m and 4 deg)\n");
  nlohmann::json maperr = nlohmann::json::array();
  const std::vector<std::pair<std::string, std::function<void(std::vector<Segment>*)>>> edits = {
      {"map as built", {}},
      {"inner partition moved 0.3 m east", [](std::vector<Segment>* m) {
         for (Segment& s : *m) {
           if (Near(s, 6.5, 6.3, 6.5, 12.8)) { s.a.x() += 0.3; s.b.x() += 0.3; }
           if (Near(s, 20, 6.3, 6.5, 6.3)) { (s.a.x() < 7 ? s.a : s.b).x() += 0.3; }
           if (Near(s, 6.5, 12.8, 20, 12.8)) { (s.a.x() < 7 ? s.a : s.b).x() += 0.3; }
         }
       }},
      {"north wall (19.5 m) missing", [](std::vector<Segment>* m) {
         std::erase_if(*m, [](const Segment& s) { return Near(s, 20, 18.8, 0.5, 18.8); });
       }},
      {"inner partition (6.5 m) missing", [](std::vector<Segment>* m) {
         std::erase_if(*m, [](const Segment& s) { return Near(s, 6.5, 6.3, 6.5, 12.8); });
       }}};
  for (const auto& [name, edit] : edits) {
    Tally f, i;
    RunBoth(MockupScenes(draws, edit), fpeb::MockupCyclone(2048), 0.5, DegToRad(4.0), false,
            FeaturePoseEstimatorOptions(), &f, &i, 13);
    PrintRow(name.c_str(), f, i);
    maperr.push_back({{"map", name}, {"fpe", f.Json()}, {"ipe", i.Json()}});
  }
  report["map_errors"] = maperr;

  // 5. The unstructured mine.
  // Default options, as everywhere in this bench: FPE measures the Typhoon's noise from each
  // scan (measure_range_noise); before it, this section had to tell it 4.4 cm.
  std::printf("\n5. Mines (2048-point Typhoon, initial error up to 0.5 m and 4 deg; FPE's noise measured from each scan)\n");
  const FeaturePoseEstimatorOptions typhoon;
  nlohmann::json mines = nlohmann::json::array();
  {
    std::vector<Scene> synthetic, research;
    for (int d = 0; d < draws; ++d) {
      MineOptions mo;
      mo.seed = static_cast<uint64_t>(d + 1);
      Scene sc;
      sc.map = sc.world = GenerateRoomAndPillarMine(mo);
      for (const Station& st : MineSurveyStations(mo)) sc.stations.push_back(st.pose);
      synthetic.push_back(sc);
      ResearchMineOptions ro;
      ro.seed = static_cast<uint64_t>(d + 1);
      Scene rs;
      rs.map = rs.world = GenerateResearchMine(ro);
      for (const Station& st : ResearchMineStations(ro)) rs.stations.push_back(st.pose);
      research.push_back(rs);
    }
    Tally fm, im;
    RunBoth(MockupScenes(draws), LadarModel::Typhoon(), 0.5, DegToRad(4.0), false, typhoon, &fm, &im, 14);
    for (const auto& [name, scenes] : {std::pair<std::string, const std::vector<Scene>*>{"room-and-pillar (5.2.1)", &synthetic},
                                       std::pair<std::string, const std::vector<Scene>*>{"research mine (5.3)", &research}}) {
      Tally f, i;
      RunBoth(*scenes, LadarModel::Typhoon(), 0.5, DegToRad(4.0), false, typhoon, &f, &i, 15);
      PrintRow(name.c_str(), f, i);
      std::printf("%-34s   FPE features per scan: corners median %.0f (mockup %.0f), lines median %.0f (mockup %.0f), matched median %.0f (mockup %.0f)\n",
                  "", fpeb::Median(f.corners), fpeb::Median(fm.corners), fpeb::Median(f.lines), fpeb::Median(fm.lines),
                  fpeb::Median(f.matches), fpeb::Median(fm.matches));
      mines.push_back({{"mine", name}, {"fpe", f.Json()}, {"ipe", i.Json()}});
    }
    PrintRow("mockup, same sensor", fm, im);
    mines.push_back({{"mine", "mockup (reference)"}, {"fpe", fm.Json()}, {"ipe", im.Json()}});
  }
  report["mines"] = mines;
  fpeb::WriteJson(args.json_out, report);
  return 0;
}
