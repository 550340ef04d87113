// Accuracy and convergence basin of the iconic pose estimator against a surveyed map.
//
//  1. Indoor mockup (2.2, Table 1): 16 stations, Cyclone noise (sigma 10 cm, 10 cm range
//     resolution, mixed pixels), clutter that is not in the map, initial errors of the size
//     Tables 1-2 show (up to 0.4 m, 2 deg). Target: max position error <= 5 cm, heading <= 0.3 deg.
//  2. Synthetic room-and-pillar mine (5.2.1): 42 stations, Typhoon noise, initial error
//     sigma 0.33 m / 3.33 deg (5.3). Target: RMS position error <= 2 cm.
//  3. Convergence basin on the mine: success rate against initial error 0.25-2 m and
//     2.5-20 deg. Target: >= 99 % for every error within 1 m and 10 deg.

#include <cstdio>
#include <random>

#include "bench/bench_util.h"
#include "common/angle.h"
#include "pose_estimator/iconic/iconic_matcher.h"
#include "pose_estimator/iconic/segment_map.h"
#include "sensor_driver/ladar_simulator.h"
#include "sim/mine_generator.h"
#include "sim/mockup_generator.h"

using namespace minenav;

namespace {

std::vector<Eigen::Vector2d> Points(const LadarScan& scan) {
  std::string problem;
  return ValidScanPoints(scan, &problem);
}

struct Errors {
  std::vector<double> position, heading_deg;
  int converged = 0, runs = 0;
};

}  // namespace

int main(int argc, char** argv) {
  const auto args = bench::ParseBenchArgs(argc, argv, "usage: ipe_accuracy [--json-out FILE] [--quick]");
  nlohmann::json report;
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);

  // --- 1. Mockup ------------------------------------------------------------------------
  {
    const MockupWorld mockup = GenerateIndoorMockup(1);
    const StaticSegmentIndex world(mockup.World());
    const LadarSimulator cyclone(LadarModel::Cyclone(2048), 5);
    CorrespondenceOptions copt;
    const auto map = MakeCorrespondenceSearch(PrepareSegmentMap(mockup.map).segments, copt);
    std::printf("1. Indoor mockup: %zu map segments, %zu clutter segments, Cyclone 2048 points\n",
                mockup.map.size(), mockup.clutter.size());
    std::printf("%-8s %10s %10s %12s %12s %10s\n", "loss", "trials", "converged", "max pos cm", "max head deg",
                "median cm");
    nlohmann::json rows = nlohmann::json::array();
    const int trials_per_station = args.quick ? 2 : 10;
    for (RobustLoss loss : {RobustLoss::kNone, RobustLoss::kHuber, RobustLoss::kCauchy}) {
      IconicMatchOptions o;
      o.loss = loss;
      o.loss_scale = 0.15;     // m, about 1.5 sigma of Cyclone noise
      o.min_threshold = 0.3;   // m, 3 sigma
      Errors e;
      std::mt19937 trial_rng(99);  // same scans and initial errors for every loss
      std::uniform_real_distribution<double> u(-1.0, 1.0);
      for (size_t s = 0; s < mockup.stations.size(); ++s) {
        const Pose2 truth = mockup.stations[s].pose;
        for (int t = 0; t < trials_per_station; ++t) {
          const LadarScan scan = cyclone.Simulate(world, truth, Pose2(), 0, static_cast<int64_t>(s * 100 + t));
          double dx, dy;
          do {
            dx = 0.4 * u(trial_rng);
            dy = 0.4 * u(trial_rng);
          } while (dx * dx + dy * dy > 0.16);
          const Pose2 initial(truth.x + dx, truth.y + dy, truth.theta + DegToRad(2.0) * u(trial_rng));
          const IconicMatchResult r = MatchPointsToMap(Points(scan), *map, initial, o);
          ++e.runs;
          e.converged += r.converged;
          e.position.push_back(TranslationDistance(r.pose, truth));
          e.heading_deg.push_back(RadToDeg(HeadingDistance(r.pose, truth)));
        }
      }
      const bool met = bench::Max(e.position) <= 0.05 && bench::Max(e.heading_deg) <= 0.3 && e.converged == e.runs;
      std::printf("%-8s %10d %10d %12.2f %12.3f %10.2f  %s\n", ToString(loss), e.runs, e.converged,
                  bench::Max(e.position) * 100, bench::Max(e.heading_deg), bench::Median(e.position) * 100,
                  bench::Verdict(met));
      rows.push_back({{"loss", ToString(loss)},
                      {"trials", e.runs},
                      {"converged", e.converged},
                      {"max_position_m", bench::Max(e.position)},
                      {"max_heading_deg", bench::Max(e.heading_deg)},
                      {"median_position_m", bench::Median(e.position)},
                      {"rms_position_m", bench::Rms(e.position)},
                      {"target_met", met}});
    }
    std::printf("thesis Table 4 (real Cyclone data): max 30 cm, 1.8 deg. Target: max <= 5 cm and <= 0.3 deg\n\n");
    report["mockup"] = rows;
  }

  // --- 2 and 3. Synthetic mine ---------------------------------------------------------------
  MineOptions mine;
  const std::vector<Segment> mine_map = PrepareSegmentMap(GenerateRoomAndPillarMine(mine)).segments;
  const std::vector<Station> stations = MineSurveyStations(mine, 42);
  const StaticSegmentIndex mine_world(mine_map);
  const LadarSimulator typhoon(LadarModel::Typhoon(), 17);
  CorrespondenceOptions copt;
  copt.max_distance = 3.0;
  const auto map = MakeCorrespondenceSearch(mine_map, copt);
  IconicMatchOptions o;
  o.min_threshold = 0.15;  // m, about 3 sigma of Typhoon noise
  o.initial_threshold = 3.0;
  {
    std::normal_distribution<double> pos(0.0, 0.33), ang(0.0, DegToRad(3.33));
    Errors e;
    for (size_t s = 0; s < stations.size(); ++s) {
      const Pose2 truth = stations[s].pose;
      const LadarScan scan = typhoon.Simulate(mine_world, truth, Pose2(), 0, static_cast<int64_t>(s));
      const Pose2 initial(truth.x + pos(rng), truth.y + pos(rng), truth.theta + ang(rng));
      const IconicMatchResult r = MatchPointsToMap(Points(scan), *map, initial, o);
      ++e.runs;
      e.converged += r.converged;
      e.position.push_back(TranslationDistance(r.pose, truth));
      e.heading_deg.push_back(RadToDeg(HeadingDistance(r.pose, truth)));
    }
    const double rms = bench::Rms(e.position);
    std::printf("2. Synthetic mine: %zu segments, 42 stations, Typhoon, initial sigma 0.33 m / 3.33 deg\n",
                mine_map.size());
    std::printf("   converged %d/%d, RMS position %.2f cm, max %.2f cm, RMS heading %.3f deg, max %.3f deg\n",
                e.converged, e.runs, rms * 100, bench::Max(e.position) * 100, bench::Rms(e.heading_deg),
                bench::Max(e.heading_deg));
    std::printf("   target: RMS position <= 2 cm: %s\n\n", bench::Verdict(rms <= 0.02 && e.converged == e.runs));
    report["mine"] = {{"stations", e.runs},
                      {"converged", e.converged},
                      {"rms_position_m", rms},
                      {"max_position_m", bench::Max(e.position)},
                      {"rms_heading_deg", bench::Rms(e.heading_deg)},
                      {"max_heading_deg", bench::Max(e.heading_deg)},
                      {"target_met", rms <= 0.02 && e.converged == e.runs}};
  }
  {
    const std::vector<double> pos_errors = {0.25, 0.5, 1.0, 2.0};
    const std::vector<double> head_errors = {2.5, 5.0, 10.0, 20.0};
    const int trials = args.quick ? 10 : 100;
    std::vector<LadarScan> scans;
    for (size_t s = 0; s < stations.size(); ++s)
      scans.push_back(typhoon.Simulate(mine_world, stations[s].pose, Pose2(), 0, static_cast<int64_t>(1000 + s)));
    std::printf("3. Convergence basin on the mine: success = converged and within 5 cm / 0.5 deg; %d trials per cell\n",
                trials);
    std::printf("%10s", "pos \\ deg");
    for (double h : head_errors) std::printf(" %8.1f", h);
    std::printf("\n");
    nlohmann::json cells = nlohmann::json::array();
    int inside_ok = 0, inside_total = 0;
    for (double pe : pos_errors) {
      std::printf("%8.2f m", pe);
      for (double he : head_errors) {
        int ok = 0;
        for (int t = 0; t < trials; ++t) {
          const size_t s = static_cast<size_t>(t) % stations.size();
          const Pose2 truth = stations[s].pose;
          const double dir = kPi * unit(rng);
          const double sign = unit(rng) < 0 ? -1.0 : 1.0;
          const Pose2 initial(truth.x + pe * std::cos(dir), truth.y + pe * std::sin(dir),
                              truth.theta + sign * DegToRad(he));
          const IconicMatchResult r = MatchPointsToMap(Points(scans[s]), *map, initial, o);
          ok += r.converged && TranslationDistance(r.pose, truth) < 0.05 &&
                HeadingDistance(r.pose, truth) < DegToRad(0.5);
        }
        const double rate = static_cast<double>(ok) / trials;
        std::printf(" %7.1f%%", 100 * rate);
        cells.push_back({{"position_error_m", pe}, {"heading_error_deg", he}, {"success_rate", rate}, {"trials", trials}});
        if (pe <= 1.0 && he <= 10.0) {
          inside_ok += ok;
          inside_total += trials;
        }
      }
      std::printf("\n");
    }
    const double inside_rate = static_cast<double>(inside_ok) / inside_total;
    std::printf("   within 1 m and 10 deg: %.1f%% of %d trials; target >= 99%%: %s\n", 100 * inside_rate, inside_total,
                bench::Verdict(inside_rate >= 0.99));
    report["basin"] = {{"cells", cells}, {"within_1m_10deg_rate", inside_rate}, {"target_met", inside_rate >= 0.99}};
  }
  bench::WriteJson(args.json_out, report);
  return 0;
}
