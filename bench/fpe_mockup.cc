// The test run of thesis 2.2 again, simulated: the indoor mockup (corridor ~6 m wide,
// concrete columns, clutter not in the map), the 16 stations of Table 1, Cyclone noise.
// Prints Table 3's columns (error in x, y, theta and position) for the first noise draw,
// then the statistics over all draws, and the time per estimate split into prediction,
// extraction, matching and minimisation (the thesis: 60 ms, 2 s, 1 s on a 68030).
// Targets: max position error <= 5 cm and max heading error <= 0.5 deg (thesis: 39 cm,
// 1.9 deg). Initial estimates: truth + uniform error up to 0.5 m and 4 deg (dead reckoning
// within the thesis's bounds poserr = 1 m, angerr = 5 deg, which the matcher uses).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>

#include "bench/fpe_bench_util.h"

using namespace minenav;

int main(int argc, char** argv) {
  const auto args = fpeb::ParseBenchArgs(argc, argv, "usage: fpe_mockup [--json-out FILE] [--quick]");
  const int draws = args.quick ? 3 : 20;  // scans (noise and clutter draws) per station
  const int points = 2048;
  const double init_pos = 0.5, init_heading = DegToRad(4.0);

  FeaturePoseEstimatorOptions options;  // the thesis's parameters are the defaults
  // Per-stage wall time (the library reads no clock of its own).
  options.stage_clock = [] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  };
  nlohmann::json report;
  report["points"] = points;
  report["draws_per_station"] = draws;
  report["initial_error"] = {{"position_m", init_pos}, {"heading_deg", RadToDeg(init_heading)}};

  std::vector<double> pos_err, head_err, t_pred, t_extr, t_match, t_min, t_ver, t_total;
  std::vector<double> corners, lines, matches, noise;
  int converged = 0, total = 0;
  nlohmann::json table = nlohmann::json::array();
  std::printf("Table 3 (simulated, first draw): error per station\n");
  std::printf("%3s %10s %10s %12s %12s %8s %6s\n", "st", "x err cm", "y err cm", "theta err deg",
              "position cm", "matches", "conv");
  std::mt19937 rng(2026);
  for (int draw = 0; draw < draws; ++draw) {
    const MockupWorld mockup = GenerateIndoorMockup(static_cast<uint64_t>(draw + 1));
    const FeaturePoseEstimator fpe(mockup.map, options);
    const LadarSimulator sim(fpeb::MockupCyclone(points), static_cast<uint64_t>(100 + draw));
    const StaticSegmentIndex world(mockup.World());
    for (size_t k = 0; k < mockup.stations.size(); ++k) {
      const Pose2 truth = mockup.stations[k].pose;
      const LadarScan scan = sim.Simulate(world, truth, Pose2(), static_cast<int64_t>(k), static_cast<int64_t>(k));
      const Pose2 initial = fpeb::Perturb(truth, init_pos, init_heading, &rng);
      FeaturePoseResult r;
      const fpeb::Outcome o = fpeb::RunFpe(fpe, scan, initial, truth, &r);
      ++total;
      corners.push_back(r.sensed_corners);
      lines.push_back(r.sensed_lines);
      matches.push_back(r.matches);
      noise.push_back(r.range_noise);
      t_pred.push_back(r.timings.prediction);
      t_extr.push_back(r.timings.extraction);
      t_match.push_back(r.timings.matching);
      t_min.push_back(r.timings.minimization);
      t_ver.push_back(r.timings.verification);
      t_total.push_back(r.timings.total());
      if (o.converged) {
        ++converged;
        pos_err.push_back(o.position_error);
        head_err.push_back(std::abs(o.heading_error));
      }
      if (draw == 0) {
        std::printf("%3zu %10.1f %10.1f %12.2f %12.1f %8d %6s  %s\n", k + 1, 100 * o.xy_error.x(),
                    100 * o.xy_error.y(), RadToDeg(o.heading_error), 100 * o.position_error, r.matches,
                    o.converged ? "yes" : "no", o.converged ? "" : r.status.c_str());
        table.push_back({{"station", k + 1}, {"x_err_cm", 100 * o.xy_error.x()}, {"y_err_cm", 100 * o.xy_error.y()},
                         {"theta_err_deg", RadToDeg(o.heading_error)}, {"position_err_cm", 100 * o.position_error},
                         {"converged", o.converged}, {"matches", r.matches}, {"reason", r.status}});
      }
    }
  }
  const double max_pos = fpeb::Max(pos_err), max_head = fpeb::Max(head_err);
  std::printf("\nAll %d estimates (%d draws x 16 stations): converged %d (%.1f%%)\n", total, draws, converged,
              fpeb::Percent(converged, total));
  std::printf("position error cm: median %.1f  max %.1f   (target max <= 5: %s; thesis max 39, typ. 18)\n",
              100 * fpeb::Median(pos_err), 100 * max_pos, fpeb::Verdict(converged == total && max_pos <= 0.05));
  std::printf("heading error deg: median %.2f  max %.2f  (target max <= 0.5: %s; thesis max 1.9)\n",
              RadToDeg(fpeb::Median(head_err)), RadToDeg(max_head),
              fpeb::Verdict(converged == total && max_head <= DegToRad(0.5)));
  std::printf("features per scan (median): corners %.0f  lines %.0f  matched %.0f\n", fpeb::Median(corners),
              fpeb::Median(lines), fpeb::Median(matches));
  std::printf("range noise measured from the scans (m): median %.4f  min %.4f  max %.4f\n", fpeb::Median(noise),
              *std::min_element(noise.begin(), noise.end()), *std::max_element(noise.begin(), noise.end()));
  std::printf("time per estimate ms (median): prediction %.3f  extraction %.3f  matching %.3f  minimisation %.3f  verification %.3f  total %.3f\n",
              1e3 * fpeb::Median(t_pred), 1e3 * fpeb::Median(t_extr), 1e3 * fpeb::Median(t_match),
              1e3 * fpeb::Median(t_min), 1e3 * fpeb::Median(t_ver), 1e3 * fpeb::Median(t_total));
  std::printf("(thesis, 20 MHz 68030: prediction 60 ms, extraction 2 s, matching + estimation 1 s)\n");
  report["table3_first_draw"] = table;
  report["estimates"] = total;
  report["converged"] = converged;
  report["position_error_cm"] = {{"median", 100 * fpeb::Median(pos_err)}, {"max", 100 * max_pos}};
  report["heading_error_deg"] = {{"median", RadToDeg(fpeb::Median(head_err))}, {"max", RadToDeg(max_head)}};
  report["range_noise_m"] = {{"median", fpeb::Median(noise)},
                             {"min", *std::min_element(noise.begin(), noise.end())},
                             {"max", *std::max_element(noise.begin(), noise.end())}};
  report["features_median"] = {{"corners", fpeb::Median(corners)}, {"lines", fpeb::Median(lines)}, {"matches", fpeb::Median(matches)}};
  report["time_ms_median"] = {{"prediction", 1e3 * fpeb::Median(t_pred)}, {"extraction", 1e3 * fpeb::Median(t_extr)},
                              {"matching", 1e3 * fpeb::Median(t_match)}, {"minimisation", 1e3 * fpeb::Median(t_min)}, {"verification", 1e3 * fpeb::Median(t_ver)},
                              {"total", 1e3 * fpeb::Median(t_total)}};
  report["targets"] = {{"max_position_5cm", converged == total && max_pos <= 0.05},
                       {"max_heading_0.5deg", converged == total && max_head <= DegToRad(0.5)}};
  fpeb::WriteJson(args.json_out, report);
  return 0;
}
