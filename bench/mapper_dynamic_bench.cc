// Contour mapper in a changing world (thesis 4.8, Figure 23): the scenarios of
// sim/changing_world.h (doors opened, a door closed, a vending machine placed and removed,
// equipment driven away, a coal face advanced), Typhoon 2048-point scans with noise and
// mixed pixels, initial poses = truth + N(0, sigma). Each scenario runs twice: with the
// dynamic-world editing (splicing of 4.8.1, removal of 4.8.2: the defaults) and without
// (static map expansion only). Reported per check: map deviation from the new world (mean,
// max), coverage of the new world's visible walls, wall length wrongly kept (seen through,
// still mapped), wall length wrongly removed (seen before, still there, missing), of which
// hidden (occluded now: must be left alone).
//
//   mapper_dynamic_bench [--seed 1] [--scenario all] [--sigma_xy 0.1] [--sigma_theta_deg 1]
//                        [--json_out FILE]

#include <cstdio>
#include <ctime>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "common/config.h"
#include "common/file_io.h"
#include "evaluation/changing_world_judge.h"
#include "sensor_driver/ladar_simulator.h"

namespace {

namespace mapper = minenav::mapper;
using minenav::Pose2;

int Run(int argc, char** argv) {
  int seed = 1;
  double sigma_xy = 0.1, sigma_theta_deg = 1.0;
  std::string scenario = "all", json_out;
  minenav::ConfigSchema schema("mapper_dynamic_bench", "Contour mapper in a changing world (thesis 4.8).");
  schema.AddInt("seed", &seed, "seed of the scans and the initial-pose noise", 0, 1000000);
  schema.AddString("scenario", &scenario, "one scenario name of sim/changing_world.h, or 'all'");
  schema.AddDouble("sigma_xy", &sigma_xy, "m", "initial pose noise, x and y", 0.0, 2.0);
  schema.AddDouble("sigma_theta_deg", &sigma_theta_deg, "deg", "initial heading noise", 0.0, 20.0);
  schema.AddString("json_out", &json_out, "write the results as JSON to this file ('' = none)");
  if (schema.Parse(argc, argv) == minenav::ParseOutcome::kExit) return 0;

  std::vector<minenav::ChangingWorldScenario> scenarios;
  if (scenario == "all")
    scenarios = minenav::AllChangingWorldScenarios();
  else
    scenarios.push_back(minenav::ChangingWorldScenarioByName(scenario));  // throws on an unknown name

  const minenav::LadarSimulator sim(minenav::LadarModel::Typhoon(), static_cast<uint64_t>(seed));
  auto scan_of = [&](const std::vector<minenav::Segment>& world, const Pose2& pose, int k) {
    return sim.Simulate(world, pose, Pose2(), static_cast<int64_t>(k) * 100000, static_cast<int64_t>(k));
  };
  mapper::ContourMapperOptions dynamic_options;
  dynamic_options.disappearance.beam_divergence = minenav::LadarModel::Typhoon().beam_divergence;
  mapper::ContourMapperOptions static_options = dynamic_options;
  static_options.expansion.splice_interior = false;
  static_options.disappearance.enabled = false;

  std::printf("mapper_dynamic_bench: Typhoon 2048 points, initial noise %.2f m / %.2f deg, seed %d\n", sigma_xy,
              sigma_theta_deg, seed);
  std::printf("%-17s %-29s %-7s %7s %7s %7s %8s %8s %8s %8s %8s %6s\n", "scenario", "check", "editing", "dev.mean",
              "dev.max", "cover", "go(m)", "kept(m)", "stay(m)", "lost(m)", "hid.lost", "cpu s");
  nlohmann::json results = nlohmann::json::array();
  for (const minenav::ChangingWorldScenario& sc : scenarios) {
    for (const bool dynamic : {true, false}) {
      const std::clock_t c0 = std::clock();
      const mapper::testing::ScenarioRun run =
          mapper::testing::RunScenario(sc, dynamic ? dynamic_options : static_options, scan_of, sigma_xy,
                                       minenav::DegToRad(sigma_theta_deg), static_cast<unsigned>(seed));
      const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
      for (const std::string& line : run.log) std::fprintf(stderr, "%s %s: %s\n", sc.name.c_str(),
                                                           dynamic ? "dynamic" : "static", line.c_str());
      for (const mapper::testing::CheckFigures& f : run.checks) {
        std::printf("%-17s %-29s %-7s %7.2fcm %6.1fcm %6.1f%% %8.2f %8.2f %8.2f %8.2f %8.2f %6.2f\n", sc.name.c_str(),
                    f.label.c_str(), dynamic ? "4.8" : "static", 100.0 * f.deviation_mean, 100.0 * f.deviation_max,
                    100.0 * f.coverage, f.must_go_m, f.wrongly_kept_m, f.must_stay_m, f.wrongly_removed_m,
                    f.hidden_removed_m, cpu);
        results.push_back({{"scenario", sc.name},
                           {"check", f.label},
                           {"editing", dynamic ? "4.8" : "static"},
                           {"deviation_mean_m", f.deviation_mean},
                           {"deviation_max_m", f.deviation_max},
                           {"coverage_within_10cm", f.coverage},
                           {"must_go_m", f.must_go_m},
                           {"wrongly_kept_m", f.wrongly_kept_m},
                           {"must_stay_m", f.must_stay_m},
                           {"wrongly_removed_m", f.wrongly_removed_m},
                           {"hidden_m", f.hidden_m},
                           {"hidden_removed_m", f.hidden_removed_m},
                           {"contours", f.contours},
                           {"scans_refused", run.refused},
                           {"max_pose_error_m", run.max_pose_error},
                           {"max_heading_error_deg", minenav::RadToDeg(run.max_heading_error)},
                           {"cpu_s", cpu}});
      }
      if (run.refused > 0) std::printf("  (%s, %s: %d scans refused)\n", sc.name.c_str(), dynamic ? "4.8" : "static", run.refused);
    }
  }
  std::printf("go = wall gone and seen through; kept = of it still mapped; stay = wall seen earlier and still there;\n"
              "lost = of it missing from the map (wrongly removed); hid.lost = of the lost, the part hidden now.\n");
  if (!json_out.empty()) {
    nlohmann::json j;
    j["benchmark"] = "mapper_dynamic_bench";
    j["seed"] = seed;
    j["initial_noise"] = {{"sigma_xy_m", sigma_xy}, {"sigma_theta_deg", sigma_theta_deg}};
    j["results"] = results;
    minenav::WriteFileAtomically(json_out, j.dump(2) + "\n");
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return minenav::bench::RunBenchMain("mapper_dynamic_bench", Run, argc, argv); }
